# help: metrics: ATE/RPE of TUM or KITTI trajectories, object-map precision/recall/F1, transform error, bandwidth, timings
main() {
  if [[ $# -eq 0 ]]; then
    set -- --help
  fi
  local exe="$SLIDE_BIN/slide-eval"
  if [[ ! -x "$exe" ]]; then
    [[ -f "$SLIDE_BUILD/CMakeCache.txt" ]] || cmake -S "$SLIDE_ROOT" -B "$SLIDE_BUILD" -DCMAKE_BUILD_TYPE=Release >/dev/null
    cmake --build "$SLIDE_BUILD" --target slide-eval -- --no-print-directory >/dev/null || die "eval: cannot build slide-eval"
  fi
  exec "$exe" "$@"
}
