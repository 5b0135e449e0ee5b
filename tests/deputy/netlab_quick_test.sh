#!/usr/bin/env bash
# ctest: ./slide netlab with three namespaced deputies and a base sheriff. Host 2's link is cut
# and host 3 gets 100% loss, so the status taken meanwhile must hear robot1 only; the stop
# script (after links are restored) must stop all three. Usage: netlab_quick_test.sh SRC BUILD
set -euo pipefail
src=$1 build=$2
if [[ $(id -u) -ne 0 ]]; then echo "skipped: needs root"; exit 77; fi
out=$(mktemp)
trap 'rm -f "$out"' EXIT
SLIDE_BUILD=$build "$src/slide" netlab --config "$src/tests/deputy/fixtures/netlab_quick.pmd" \
  --schedule "0 cut 2; 0 loss 3 100" --duration 1.5 --wait-timeout 10 >"$out" 2>&1 || { cat "$out"; exit 1; }
cat "$out"
fail() { echo "FAILED: $*"; exit 1; }
status=$(sed -n '/netlab: status/,/sheriff script .stop./p' "$out")
grep -Eq 'robot1 +worker +robots +running' <<<"$status" || fail "robot1 not running in the status"
grep -Eq 'robot2 +worker +robots +no deputy' <<<"$status" || fail "robot2 heard through a cut link"
grep -Eq 'robot3 +worker +robots +no deputy' <<<"$status" || fail "robot3 heard through 100% loss"
[[ $(grep -Ec 'robot[123] +worker +robots +stopped \(ok\)' "$out") -eq 3 ]] || fail "stop script did not stop all three"
prefix=$(grep -o 'namespaces slnl[0-9]*' "$out" | head -1 | cut -d' ' -f2)
[[ -n "$prefix" ]] || fail "no namespace prefix in the log"
if ip netns list | grep -q "^$prefix-"; then fail "namespaces $prefix-* left behind"; fi
echo "netlab quick test passed"
