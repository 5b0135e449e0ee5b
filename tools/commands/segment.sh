# help: one LiDAR scan through the segmenter and shape fits: objects as JSON, a picture, a score against labels
main() {
  if [[ $# -eq 0 ]] || wants_help "$@"; then
    cat <<USAGE
usage: ./slide segment SCAN [--labels L] [--mode geometric|learned|labelled] [--sensor-fov UP DOWN] [--plot out.png]
                          [--json out.json] [--explain]
Reads one scan (KITTI velodyne .bin, .pcd, or a text file with 'x y z [intensity]' per line),
segments it (default: geometric, label-free; learned: the range-image model of config/frontend.yaml's
segmenter.learned labels the points, give the scan's vertical field of view with --sensor-fov,
e.g. 3 -25 for KITTI's HDL-64E) and fits the shape models (cars as cuboids,
trunks and poles as cylinders, the rest as ellipsoids). Prints one JSON object: the objects
found (class, shape, position, size, points) and, with --labels (SemanticKITTI .label), how
they score against the labelled cars (>= 200 points) and trunk/pole groups (>= 30 points):
found, duplicates and false objects. --plot draws the points and objects from above.
Parameters: config/frontend.yaml and config/classes.yaml (--config, --classes to override).
Exit code 1 when a file cannot be read (the message names it).
Example:
  ./slide segment ../shared/data/semantickitti/sequences/08/velodyne/000720.bin \\
      --labels ../shared/data/semantickitti/sequences/08/labels/000720.label --plot scan.png
  ./slide segment ../shared/data/semantickitti/sequences/08/velodyne/000720.bin --mode learned --sensor-fov 3 -25
More options: build/bin/slide-segment --help
USAGE
    [[ $# -eq 0 ]] && return 1
    return 0
  fi
  ensure_built >&2  # keep stdout for the one JSON object
  "$SLIDE_BIN/slide-segment" "$@"
}
