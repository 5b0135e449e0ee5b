# help: simulate a multi-robot dataset (forest, urban, indoor, kitti05, kitti07; LiDAR or RGBD)
# Builds slide-sim when needed, then runs it; all options go to slide-sim.
sim_build() {
  install_packages
  if [[ ! -f "$SLIDE_BUILD/CMakeCache.txt" ]]; then
    cmake -S "$SLIDE_ROOT" -B "$SLIDE_BUILD" -DCMAKE_BUILD_TYPE=Release >/dev/null
  fi
  cmake --build "$SLIDE_BUILD" -j "$(nproc)" --target slide-sim -- --no-print-directory >&2
}

main() {
  if wants_help "$@"; then
    cat <<USAGE
usage: ./slide sim --world forest|urban|indoor|kitti05|kitti07 --out DIR [options]

Writes OUT/objects.csv (ground-truth objects), OUT/world.yaml and one folder per robot,
OUT/robotN/: odom.txt (odometry, TUM, the robot's own frame), groundtruth.txt (TUM, world
frame), robot.yaml, and either KITTI-layout LiDAR scans (velodyne/, labels/, poses.txt,
times.txt, calib.txt) or TUM-layout RGBD frames (rgb/, depth/, instances/, associations.txt,
calib.txt). Replay a robot with: build/bin/slide-sensor-driver OUT/robot0 --robot 0

examples:
  ./slide sim --world forest --robots 3 --distance 300 --out /tmp/forest
  ./slide sim --world forest --forest-layout longleaf --side 200 --aerial --out /tmp/longleaf
  ./slide sim --world urban --robots 2 --frames 600 --lidar hdl-64e --out /tmp/urban
  ./slide sim --world indoor --robots 3 --sensor rgbd --camera d455 --frames 300 --out /tmp/indoor
  ./slide sim --world kitti07 --robots 3 --out /tmp/kitti07   (the paper's splits: 0-600, 400-1000, 500-1100)

options of slide-sim:
USAGE
    sim_build >/dev/null 2>&1 && "$SLIDE_BIN/slide-sim" --help | sed -n '/^Options:/,$p'
    return 0
  fi
  sim_build
  "$SLIDE_BIN/slide-sim" "$@"
}
