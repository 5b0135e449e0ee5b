# help: build if needed, then run the default test suite with ctest (extra args go to ctest)
main() {
  if wants_help "$@"; then
    cat <<USAGE
usage: ./slide test [ctest options]
Runs setup when needed, then the default suite: ctest -LE scenario. Options pass to ctest,
e.g. ./slide test -R Kdtree, or ./slide test -L scenario for the long scenario runs only.
USAGE
    return 0
  fi
  ensure_built
  local label_args=(-LE scenario)
  local a
  for a in "$@"; do [[ "$a" == "-L" ]] && label_args=(); done
  cd "$SLIDE_BUILD"
  ctest --output-on-failure -j "$(nproc)" "${label_args[@]}" "$@"
}
