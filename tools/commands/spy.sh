# help: lcm-spy with the project's message types (builds the types jar, runs lcm.spy.Spy directly)
main() {
  if wants_help "$@"; then
    cat <<USAGE
usage: ./slide spy [--lcm-url URL] [--headless-check SEC]
Builds build/slide_lcmtypes.jar (target slide_lcmtypes_jar: every type of lcmtypes/, including
procman_lcm) and starts java lcm.spy.Spy with it. Debian's lcm-spy script cannot start on
Java 17 (it passes the removed -Xincgc option) and points at jchart2d.jar, which Debian does
not ship. Without jchart2d the channel table (rates, bandwidth, types) works; the per-channel
message viewer and its plots need jchart2d: set JCHART2D_JAR=/path/jchart2d.jar to add it.
Default URL: udpm://239.255.76.67:7667?ttl=0 (the procman bus; robot N's bus is port 767N).
--headless-check SEC runs Spy for SEC seconds under xvfb-run and reports whether it started.
USAGE
    return 0
  fi
  local url="udpm://239.255.76.67:7667?ttl=0" check=""
  while [[ $# -gt 0 ]]; do
    case "$1" in
      --lcm-url) url=$2; shift 2 ;;
      --headless-check) check=$2; shift 2 ;;
      *) die "spy: unknown option '$1' (see ./slide spy --help)" ;;
    esac
  done
  [[ -f "$SLIDE_BUILD/CMakeCache.txt" ]] || ensure_built
  cmake --build "$SLIDE_BUILD" --target slide_lcmtypes_jar -- --no-print-directory >/dev/null ||
    die "spy: cannot build the types jar (needs javac and /usr/share/java/lcm.jar: liblcm-java, default-jdk-headless)"
  local cp="/usr/share/java/lcm.jar:$SLIDE_BUILD/slide_lcmtypes.jar"
  local chart="${JCHART2D_JAR:-/usr/share/java/jchart2d.jar}"
  if [[ -f "$chart" ]]; then cp="$cp:$chart"; else log "spy: no jchart2d.jar: channel table only, no message viewer/plots"; fi
  local -a java_cmd=(java -Djava.net.preferIPv4Stack=true -Xmx256m -cp "$cp" lcm.spy.Spy --lcm-url "$url")
  if [[ -n "$check" ]]; then
    command -v xvfb-run >/dev/null || die "spy: --headless-check needs xvfb-run (Debian package xvfb)"
    local out rc=0
    out=$(timeout "$check" xvfb-run -a "${java_cmd[@]}" 2>&1) || rc=$?
    grep -E "Found [0-9]+ LCM types" <<<"$out" || true
    if grep -q "Exception" <<<"$(grep -v ClassDiscoverer <<<"$out")"; then
      grep -v -E "ClassDiscoverer|^ +(jar|class):" <<<"$out" >&2
      die "spy: lcm.spy.Spy failed to start"
    fi
    [[ $rc -eq 124 ]] || die "spy: lcm.spy.Spy exited early (status $rc)"
    log "spy: lcm.spy.Spy ran for ${check}s without errors"
    return 0
  fi
  [[ -n "${DISPLAY:-}" ]] || die "spy: no DISPLAY (use ssh -X, or xvfb-run ./slide spy for a virtual one)"
  # Spy scans the class path and warns about every class that needs jchart2d: drop that noise.
  "${java_cmd[@]}" 2> >(grep -v -E "ClassDiscoverer|^ +(jar|class):" >&2)
}
