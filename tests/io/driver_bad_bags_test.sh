#!/usr/bin/env bash
# slide-sensor-driver as a process on truncated, byte-corrupted and partly broken ROS 1 bags
# (log only, nothing on the network): it exits 0 having dropped and counted unreadable
# frames, or 1 with an error naming the bag; never a signal, an abort or a hang.
set -euo pipefail
BIN=$1 SRC=$2
OUT=$(mktemp -d /tmp/slide_bad_bags.XXXXXX)
trap 'rm -rf "$OUT"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
/usr/bin/python3 "$SRC/tests/io/make_bags.py" "$OUT" --only velodyne
/usr/bin/python3 "$SRC/tests/io/make_bags.py" "$OUT" --only broken

# drive BAG ARGS...: runs the driver into a log; sets rc; fails on a signal or a hang.
drive() {
  local bag=$1
  shift
  rc=0
  timeout 60 "$BIN/slide-sensor-driver" "$bag" --no-publish --log "$OUT/out.lcmlog" --rate 0 --no-progress "$@" \
    >"$OUT/stdout" 2>"$OUT/stderr" || rc=$?
  [[ $rc -ne 124 ]] || fail "$(basename "$bag"): the driver hung"
  [[ $rc -lt 128 ]] || fail "$(basename "$bag"): the driver died of signal $((rc - 128)): $(tail -3 "$OUT/stderr")"
  [[ $rc -eq 0 || $rc -eq 1 ]] || fail "$(basename "$bag"): exit status $rc"
  if [[ $rc -eq 1 ]]; then grep -q "$(basename "$bag")" "$OUT/stderr" || fail "$(basename "$bag"): error does not name the bag: $(cat "$OUT/stderr")"; fi
  return 0
}
velodyne=(--cloud-topic /velodyne_points --max-odom-gap 0.2)

# A bag cut anywhere: an error naming it (the index is at the end).
size=$(stat -c %s "$OUT/velodyne.bag")
for keep in 0 13 4096 $((size / 2)) $((size - 100)); do
  head -c "$keep" "$OUT/velodyne.bag" > "$OUT/cut.bag"
  drive "$OUT/cut.bag" "${velodyne[@]}"
  [[ $rc -eq 1 ]] || fail "a bag cut to $keep of $size bytes was read without an error"
done

# Bytes overwritten at random (fixed seeds): an error naming the bag, or a replay (frames
# dropped and counted).
opened=0
for seed in $(seq 1 25); do
  /usr/bin/python3 - "$OUT/velodyne.bag" "$OUT/bad.bag" "$seed" <<'PY'
import random, sys
data = bytearray(open(sys.argv[1], "rb").read())
rng = random.Random(int(sys.argv[3]))
n = len(data)
for _ in range(8):  # anywhere (mostly point data), and in the header, connection and index records
    data[rng.randrange(n)] = rng.randrange(256)
    data[rng.randrange(8192) if rng.random() < 0.5 else n - 1 - rng.randrange(8192)] = rng.randrange(256)
open(sys.argv[2], "wb").write(bytes(data))
PY
  drive "$OUT/bad.bag" "${velodyne[@]}"
  [[ $rc -ne 0 ]] || opened=$((opened + 1))
done

# Two broken messages in a good bag: both dropped and counted, the others sent.
drive "$OUT/broken.bag" --cloud-topic /points --odom-topic /odom
[[ $rc -eq 0 ]] || fail "broken.bag: exit $rc: $(cat "$OUT/stderr")"
grep -q "frame 1 dropped: .*broken.bag: topic '/points' message 1" "$OUT/stderr" || fail "no drop of message 1: $(cat "$OUT/stderr")"
grep -q "frame 2 dropped: .*message 2" "$OUT/stderr" || fail "no drop of message 2"
grep -q "end of data: 2 frames sent" "$OUT/stderr" || fail "not 2 frames sent"
grep -q "2 frames could not be read and were dropped" "$OUT/stderr" || fail "drops not counted"
echo "driver on bad bags: no crash; $opened of 25 corrupted bags replayed"
