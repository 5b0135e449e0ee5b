# help: pictures: object maps and trajectories (top/oblique, PNG/SVG), ATE over time
main() {
  if [[ $# -eq 0 ]]; then
    set -- --help
  fi
  local exe="$SLIDE_BIN/slide-plot"
  if [[ ! -x "$exe" ]]; then
    [[ -f "$SLIDE_BUILD/CMakeCache.txt" ]] || cmake -S "$SLIDE_ROOT" -B "$SLIDE_BUILD" -DCMAKE_BUILD_TYPE=Release >/dev/null
    cmake --build "$SLIDE_BUILD" --target slide-plot -- --no-print-directory >/dev/null || die "plot: cannot build slide-plot"
  fi
  exec "$exe" "$@"
}
