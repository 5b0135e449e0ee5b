#!/usr/bin/env bash
# ctest: the layer check fails the configure step when a core target links a tooling target,
# also through another core target, and passes when tooling only uses the core.
# Usage: layers_check_test.sh SOURCE_DIR
set -uo pipefail
src=$1
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
if ! cmake -S "$src/tests/core/layers" -B "$tmp/ok" -DSLIDE_SOURCE_DIR="$src" >"$tmp/ok.log" 2>&1; then
  echo "FAILED: a clean layering was refused:"; cat "$tmp/ok.log"; exit 1
fi
if cmake -S "$src/tests/core/layers" -B "$tmp/bad" -DSLIDE_SOURCE_DIR="$src" -DVIOLATE=ON >"$tmp/bad.log" 2>&1; then
  echo "FAILED: core linking tooling passed the configure step"; exit 1
fi
tr -s ' \n' ' ' <"$tmp/bad.log" >"$tmp/bad.txt"  # CMake wraps its messages
grep -q "core_b is robot core .* but links tooling_t" "$tmp/bad.txt" || { echo "FAILED: no error for core_b (through core_a):"; cat "$tmp/bad.log"; exit 1; }
echo "ok: core -> tooling fails the configure step"
