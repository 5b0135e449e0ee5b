# help: place recognition between two object maps: prints the transform B -> A as JSON
main() {
  if wants_help "$@"; then
    cat <<USAGE
usage: ./slide match [--method slidegraph|slidematch] [--budget-ms MS] [--config FILE] MAP_A MAP_B
Reads two object maps (one object per line: 'label x y z [sx sy sz]', as in
../shared/data/slideslam_maps) and prints one JSON object:
  {"found": true, "method": ..., "x", "y", "z", "yaw_deg" (maps MAP_B's frame into MAP_A's),
   "inliers", "residual_rms", "chance_inliers", "ms"}
or "found": false with "reason". Parameters: config/place.yaml (--config to override).
Exit code 1 when a map cannot be read (the JSON then names the file).
Example: ./slide match ../shared/data/slideslam_maps/parking/robot0.txt ../shared/data/slideslam_maps/parking/robot1.txt
USAGE
    return 0
  fi
  ensure_built
  "$SLIDE_BIN/slide-match" "$@"
}
