#!/usr/bin/env bash
# Simulated, labelled LiDAR scans for tools/train_range_net/train.py (run by hand, not in CI).
# Usage: tools/train_range_net/make_data.sh OUT_DIR [train|heldout|kitti]
#   train:   seeds 11-14 of forest (procedural and the real stem layouts), urban, indoor, with
#            the Ouster OS1-64 and Velodyne HDL-64E, ground and aerial robots.
#   heldout: seeds 1-2 (never trained on; ./slide bench frontend evaluates seed 1).
#   kitti:   the simulated KITTI 05 (seed 11) and 07 (seed 12) worlds: real trajectories and pole
#            positions, HDL-64E at 1.73 m (KITTI's mounting); 3 robots x 250 frames at 10 Hz
#            each (train.py --extra OUT_DIR:5 takes every 5th). Not SemanticKITTI 08, whose two
#            scans ./slide bench frontend tests on.
# SIM=/path/to/slide-sim uses another build's simulator (default: this tree's build/bin).
# One frame every 2 s (0.5 Hz) keeps consecutive scans apart.
set -euo pipefail
out=${1:?usage: make_data.sh OUT_DIR [train|heldout|kitti]}
set_name=${2:-train}
root=$(cd "$(dirname "$0")/../.." && pwd)
sim=${SIM:-"$root/build/bin/slide-sim"}
[[ -x "$sim" ]] || { echo "build slide-sim first (cmake --build build --target slide-sim)" >&2; exit 1; }
if [[ "$set_name" == train ]]; then seeds=(11 12 13 14); else seeds=(1 2); fi
run() {  # name, then slide-sim options
  local name=$1; shift
  [[ -d "$out/$name/robot0/velodyne" ]] && return 0
  "$sim" --robots 1 --rate 0.5 --quiet --threads 1 --data-dir /work/shared/data --out "$out/$name" --force "$@" >/dev/null
}
if [[ "$set_name" == kitti ]]; then
  for spec in "kitti05 11" "kitti07 12"; do
    read -r world seed <<< "$spec"
    [[ -d "$out/$world-$seed/robot2/velodyne" ]] && continue
    "$sim" --world "$world" --seed "$seed" --robots 3 --frames 250 --quiet --threads 1 \
        --data-dir /work/shared/data --out "$out/$world-$seed" --force >/dev/null
  done
  echo "$out: $(find "$out" -name '*.bin' | wc -l) scans"
  exit 0
fi
for seed in "${seeds[@]}"; do
  for lidar in os1-64 hdl-64e; do
    run "forest-$seed-$lidar" --world forest --seed "$seed" --lidar "$lidar" --distance 120
    run "urban-$seed-$lidar" --world urban --seed "$seed" --lidar "$lidar" --distance 160
    run "indoor-$seed-$lidar" --world indoor --seed "$seed" --lidar "$lidar" --distance 50
  done
  layout=(longleaf finpines spruces procedural)
  run "forest-$seed-${layout[$((seed % 4))]}" --world forest --seed "$seed" --lidar os1-64 --distance 120 \
      --forest-layout "${layout[$((seed % 4))]}"
  run "forest-$seed-aerial" --world forest --seed "$seed" --lidar os1-64 --distance 120 --aerial
  run "urban-$seed-aerial" --world urban --seed "$seed" --lidar hdl-64e --distance 160 --aerial
done
echo "$out: $(find "$out" -name '*.bin' | wc -l) scans"
