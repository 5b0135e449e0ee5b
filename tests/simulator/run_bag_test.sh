#!/usr/bin/env bash
# ./slide run-bag end to end: a simulated mission written as a bag, one robot's daemons under a
# deputy and sheriff, a map with objects and its pictures at the end; the bag and the output
# live under a path with a space (quoted through the generated .pmd). Long (label scenario).
set -euo pipefail
ROOT=$1
OUT=$(mktemp -d /tmp/slide_run_bag.XXXXXX)
trap 'rm -rf "$OUT"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
"$ROOT/build/bin/slide-sim" --world forest --robots 1 --distance 40 --rate 5 --out "$OUT/sim" >/dev/null 2>&1
mkdir -p "$OUT/my bags"
SLIDE_NO_BUILD=1 "$ROOT/slide" convert "$OUT/sim/robot0" "$OUT/my bags/robot0.bag" >/dev/null
SLIDE_NO_BUILD=1 "$ROOT/slide" run-bag "$OUT/my bags/robot0.bag" --out "$OUT/my run" --rate 2 --cloud-topic /points \
  --odom-topic /odom >"$OUT/log" 2>&1 || { cat "$OUT/log"; fail "run-bag failed"; }
n=$(grep -vc '^#' "$OUT/my run/out/map_robot0.txt" || true)
[[ "$n" -gt 10 ]] || fail "map has $n objects"
[[ $(wc -l < "$OUT/my run/out/trajectory_robot0.txt") -gt 5 ]] || fail "trajectory too short"
[[ -s "$OUT/my run/map_top.png" && -s "$OUT/my run/map_oblique.png" ]] || fail "pictures missing"
echo "run-bag: $n objects"
