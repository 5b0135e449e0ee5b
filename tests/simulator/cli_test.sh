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
# Mixed teams: one sensor per robot, aerial robots by id; a list that does not fit the team fails.
"$BIN/slide-sim" --world indoor --robots 2 --frames 2 --sensors lidar,rgbd --aerial-robots 1 --out "$OUT/mixed" --quiet 2>/dev/null
[[ -s "$OUT/mixed/robot0/velodyne/000001.bin" && -s "$OUT/mixed/robot1/rgb.txt" ]] || fail "mixed team sensors"
grep -q "aerial: true" "$OUT/mixed/robot1/robot.yaml" || fail "robot 1 not aerial"
if "$BIN/slide-sim" --world indoor --robots 3 --frames 1 --sensors lidar,rgbd --out "$OUT/y" --quiet 2>"$OUT/err"; then fail "accepted 2 sensors for 3 robots"; fi
grep -q "2 sensors for 3 robots" "$OUT/err" || fail "no message naming the sensor count"
if "$BIN/slide-sim" --world indoor --robots 2 --frames 1 --aerial-robots 5 --out "$OUT/z" --quiet 2>"$OUT/err"; then fail "accepted aerial robot 5"; fi
grep -q "aerial robot 5" "$OUT/err" || fail "no message naming the aerial robot"
# The driver refuses a folder that is not a dataset, naming it.
if "$BIN/slide-sensor-driver" "$OUT" --no-publish --log "$OUT/x.lcm" 2>"$OUT/err"; then fail "driver accepted $OUT"; fi
grep -q "$OUT" "$OUT/err" || fail "driver error does not name the folder"
# Log only (no bus): the log holds the frames.
"$BIN/slide-sensor-driver" "$OUT/indoor/robot0" --no-publish --rate 0 --log "$OUT/r0.lcm" --no-progress 2>/dev/null
[[ -s "$OUT/r0.lcm" ]] || fail "empty log"
# A config file sets the channels; the log shows them.
printf 'sensor_driver:\n  rate: 0\n  channels:\n    scan: SCAN_R9\n    odom: ODOM_R9\n' > "$OUT/driver.yaml"
"$BIN/slide-sensor-driver" "$OUT/indoor/robot0" --no-publish --config "$OUT/driver.yaml" --log "$OUT/r9.lcm" --no-progress 2>/dev/null
grep -q SCAN_R9 "$OUT/r9.lcm" || fail "config channel not used"
printf 'sensor_driver:\n  rate: fast\n' > "$OUT/bad.yaml"
if "$BIN/slide-sensor-driver" "$OUT/indoor/robot0" --no-publish --config "$OUT/bad.yaml" --log "$OUT/x.lcm" 2>"$OUT/err"; then fail "bad config accepted"; fi
grep -q "rate" "$OUT/err" || fail "config error does not name the key"
echo "cli ok"
# ./slide demo refuses a run folder that holds an earlier run (its optimizers would resume that
# run's journals), naming it; the refusal comes before anything is simulated or started.
ROOT=$(cd "$(dirname "$0")/../.." && pwd)
mkdir -p "$OUT/run/state"
if SLIDE_NO_BUILD=1 "$ROOT/slide" demo --out "$OUT/run" --data "$OUT/indoor" --no-view 2>"$OUT/err"; then fail "demo reused an earlier run"; fi
grep -q "holds an earlier run" "$OUT/err" || fail "demo: no message naming the earlier run"
[[ ! -e "$OUT/run/data" ]] || fail "demo started before refusing"
