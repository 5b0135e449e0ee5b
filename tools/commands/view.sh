# help: live map viewer in the browser: robots' buses as they run, or a recorded run replayed
main() {
  if wants_help "$@"; then
    cat <<USAGE
usage: ./slide view RUN_DIR|LOG... [--follow] [viewer options]     replay a recorded run
       ./slide view --robot N [--robot M ...] [--team-url URL] [...] watch robots' buses live
Starts slide-viewer and prints its address (http://127.0.0.1:8080/ by default). A RUN_DIR is
what ./slide demo writes (its logs/robot<N>.lcmlog and logs/team<N>.lcmlog); a single LCM log is
named robot<N>*.lcmlog / team<N>*.lcmlog or given as N=LOG / team:N=LOG. Replays have pause,
speed and a time slider; --follow keeps reading logs still being written (a running demo).
The page is served on 127.0.0.1 only; from another machine tunnel it:
  ssh -L 8080:127.0.0.1:8080 robot      then open http://127.0.0.1:8080/ there.
Viewer options (build/bin/slide-viewer --help): --port, --bind, --bus N=URL, --max-clients,
--period, --max-instance-points, --log-level.
USAGE
    return 0
  fi
  local args=()
  while [[ $# -gt 0 ]]; do
    case "$1" in
      -*) args+=("$1"); [[ $# -gt 1 && "$2" != -* && "$1" != --follow ]] && { args+=("$2"); shift; } ;;
      *) args+=(--replay "$1") ;;
    esac
    shift
  done
  ensure_built
  exec "$SLIDE_BIN/slide-viewer" "${args[@]}"
}
