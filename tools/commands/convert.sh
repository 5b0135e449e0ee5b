# help: convert recordings: dataset folder <-> ROS 1 bag (LiDAR), bag or folder -> LCM event log (lcm-logplayer replays it)
main() {
  if wants_help "$@" || [[ $# -lt 2 ]]; then
    cat <<USAGE
usage: ./slide convert IN OUT [DRIVER OPTIONS...]
  IN a KITTI-layout folder, OUT *.bag     writes /points (PointCloud2) and /odom (Odometry) with
                                          python3-rosbag (tools/convert/folder_to_bag.py)
  IN a bag or folder, OUT *.lcmlog        the robot-bus messages the sensor driver would publish
                                          (SCAN/RGBD, ODOM, SENSOR_STATUS), for lcm-logplayer
  IN a LiDAR bag, OUT a new folder        a KITTI-layout folder (velodyne/*.bin in the body frame,
                                          times.txt, odom.txt at the frame times, calib.txt;
                                          slide-bag-to-folder)
DRIVER OPTIONS choose the bag's topics and frames as for slide-sensor-driver, e.g.
  --cloud-topic /points --odom-topic /odom [--deskew] [--max-odom-gap S] [--config driver.yaml]
Replay a log into running daemons: lcm-logplayer -l 'udpm://239.255.76.67:7670?ttl=0' OUT.lcmlog
Not supported: an RGBD bag -> folder, an RGBD folder -> bag (the driver reads bags directly:
./slide run-bag BAG, or slide-sensor-driver BAG).
USAGE
    [[ $# -lt 2 ]] && ! wants_help "$@" && return 1
    return 0
  fi
  local in=$1 out=$2
  shift 2
  [[ -e "$in" ]] || die "convert: $in does not exist"
  case "$out" in
    *.bag)
      [[ -d "$in" ]] || die "convert: $in is not a folder (bag -> bag is not supported)"
      [[ -d "$in/velodyne" ]] || die "convert: $in is not a KITTI-layout LiDAR folder (velodyne/)"
      /usr/bin/python3 "$SLIDE_ROOT/tools/convert/folder_to_bag.py" "$in" "$out" "$@" ;;
    *.lcmlog | *.lcm)
      [[ -n "${SLIDE_NO_BUILD:-}" ]] || ensure_built
      "$SLIDE_BIN/slide-sensor-driver" "$in" --no-publish --rate 0 --log "$out" "$@" ;;
    *)
      [[ -f "$in" && "$in" == *.bag ]] || die "convert: OUT must end in .bag or .lcmlog, or be a folder for a .bag IN"
      [[ -n "${SLIDE_NO_BUILD:-}" ]] || ensure_built
      "$SLIDE_BIN/slide-bag-to-folder" "$in" "$out" "$@" ;;
  esac
}
