#!/usr/bin/env bash
# slide-sim and slide-sensor-driver from the command line: help, a small run, bad input.
set -euo pipefail
BIN="$1"
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

"$BIN/slide-sim" --help | grep -q -- "--world" || fail "slide-sim --help"
"$BIN/slide-sensor-driver" --help | grep -q -- "--rate" || fail "slide-sensor-driver --help"
"$BIN/slide-sim" --world indoor --robots 2 --frames 3 --lidar vlp-16 --out "$OUT/indoor" --quiet 2>/dev/null
for r in 0 1; do
  for f in odom.txt groundtruth.txt poses.txt times.txt calib.txt robot.yaml velodyne/000002.bin labels/000002.label; do
    [[ -s "$OUT/indoor/robot$r/$f" ]] || fail "missing robot$r/$f"
  done
done
[[ $(wc -l < "$OUT/indoor/robot1/odom.txt") -eq 3 ]] || fail "odom.txt lines"
head -1 "$OUT/indoor/objects.csv" | grep -q '^id,class_id,shape,x,y,z,yaw' || fail "objects.csv header"
# A non-empty output folder is refused without --force; bad options fail with a message.
if "$BIN/slide-sim" --world indoor --frames 1 --out "$OUT/indoor" --quiet 2>"$OUT/err"; then fail "overwrote"; fi
grep -q "not empty" "$OUT/err" || fail "no 'not empty' message"
if "$BIN/slide-sim" --world moon --out "$OUT/x" 2>"$OUT/err"; then fail "accepted --world moon"; fi
# The driver refuses a folder that is not a dataset, naming it.
if "$BIN/slide-sensor-driver" "$OUT" --no-publish --log "$OUT/x.lcm" 2>"$OUT/err"; then fail "driver accepted $OUT"; fi
grep -q "$OUT" "$OUT/err" || fail "driver error does not name the folder"
# Log only (no bus): the log holds the frames.
"$BIN/slide-sensor-driver" "$OUT/indoor/robot0" --no-publish --rate 0 --log "$OUT/r0.lcm" --no-progress 2>/dev/null
[[ -s "$OUT/r0.lcm" ]] || fail "empty log"
echo "cli ok"
