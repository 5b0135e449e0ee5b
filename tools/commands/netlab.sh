# help: emulate N robot hosts in network namespaces: deputies, a sheriff script, link cuts and loss
source "$SLIDE_ROOT/tools/commands/lib/netlab_net.sh"

netlab_usage() {
  cat <<USAGE
usage: ./slide netlab [options]
Creates N+2 network namespaces (a bridge, a "base" for the sheriff, hosts h1..hN) joined by
veth pairs on one bridge, starts slide-deputy --id robot<i> in each host, runs a sheriff
script from the base, follows a schedule of link events, prints the status table, runs the
stop script and removes everything (also on Ctrl-C). Needs root. Nothing touches the host's
own network: all links live inside the namespaces created here.

options:
  --hosts N            robot hosts (default 3)
  --config FILE        sheriff config (default procman/team_three_hosts.pmd)
  --script NAME        script run at the start (default start)
  --stop-script NAME   script run at the end (default stop; "" for none)
  --schedule SPEC      link events, ';'-separated or one per line in a file:
                         <seconds> cut <host> | restore <host> | loss <host> <percent> | clear <host>
                         | crash <host> <text>  (SIGKILL the host's processes whose command line
                           holds <text>; the deputy respawns those with auto_respawn)
                         | script <name>  (run another sheriff script of the config)
                       seconds count from the end of the start script, e.g.
                         "2 cut 2; 6 restore 2; 8 loss 3 30; 12 clear 3"
  --duration SEC       total time after the start script (default: last event + 3, at least 3)
  --wait-timeout SEC   per wait in sheriff scripts (default 30)
  --url URL            procman LCM url inside the namespaces (default ttl=1 so it crosses hosts)
Logs go to build/netlab/<time>/ (deputy<i>.log, sheriff logs).
USAGE
}

main() {
  if wants_help "$@"; then netlab_usage; return 0; fi
  local hosts=3 config="$SLIDE_ROOT/procman/team_three_hosts.pmd" script=start stop_script=stop
  local schedule="" duration="" wait_timeout=30 url="udpm://239.255.76.67:7667?ttl=1"
  while [[ $# -gt 0 ]]; do
    case "$1" in
      --hosts) hosts=$2; shift 2 ;;
      --config) config=$2; shift 2 ;;
      --script) script=$2; shift 2 ;;
      --stop-script) stop_script=$2; shift 2 ;;
      --schedule) schedule=$2; shift 2 ;;
      --duration) duration=$2; shift 2 ;;
      --wait-timeout) wait_timeout=$2; shift 2 ;;
      --url) url=$2; shift 2 ;;
      *) die "netlab: unknown option '$1' (see ./slide netlab --help)" ;;
    esac
  done
  [[ $(id -u) -eq 0 ]] || die "netlab needs root (network namespaces)"
  [[ "$hosts" =~ ^[1-9][0-9]?$ ]] || die "netlab: --hosts must be 1..99 (got '$hosts')"
  [[ -f "$config" ]] || die "netlab: no config file $config"
  [[ -f "$schedule" ]] && schedule=$(grep -v '^\s*#' "$schedule" | tr '\n' ';')
  [[ -x "$SLIDE_BIN/slide-deputy" && -x "$SLIDE_BIN/slide-sheriff" ]] || ensure_built
  # The shipped configs read team keys from /tmp/slide-team-keys (one file per robot): make them
  # once when missing (every emulated host shares this machine's file system).
  if grep -q -- "--team-key-file /tmp/slide-team-keys/" "$config" && [[ ! -f /tmp/slide-team-keys/robot0.keys ]]; then
    [[ -x "$SLIDE_BIN/slide-team-keys" ]] || ensure_built
    "$SLIDE_BIN/slide-team-keys" --team "$(seq -s, 0 $((hosts - 1)))" --out /tmp/slide-team-keys --log-level warn \
      || die "netlab: cannot make team keys in /tmp/slide-team-keys"
  fi

  NL_PREFIX="slnl$$" NL_HOSTS=$hosts NL_DEPUTIES=() NL_WAIT_TIMEOUT=$wait_timeout
  NL_LOGDIR="$SLIDE_BUILD/netlab/$(date +%Y%m%d-%H%M%S)-$$"
  local logdir=$NL_LOGDIR
  mkdir -p "$logdir"
  trap netlab_cleanup EXIT
  trap 'log "netlab: interrupted"; exit 130' INT TERM

  log "netlab: $hosts hosts in namespaces $NL_PREFIX-*"
  nl_setup "$hosts"
  local i
  for ((i = 1; i <= hosts; i++)); do
    ( cd "$SLIDE_ROOT" && exec ip netns exec "$(nl_ns "$i")" "$SLIDE_BIN/slide-deputy" --id "robot$i" \
        --lcm-url "$url" ) >"$logdir/deputy$i.log" 2>&1 &
    NL_DEPUTIES+=($!)
  done
  sheriff() { ip netns exec "$(nl_ns 0)" "$SLIDE_BIN/slide-sheriff" -c "$config" --lcm-url "$url" "$@"; }
  local rc=0
  log "netlab: sheriff script '$script'"
  sheriff -s "$script" --wait-timeout "$wait_timeout" --deputy-timeout 10 2>&1 | tee "$logdir/sheriff_$script.log" || rc=1

  netlab_follow_schedule "$schedule" "$duration"
  log "netlab: status"
  sheriff --listen 2 2>&1 | tee "$logdir/status.log"
  if [[ -n "$stop_script" ]]; then
    for ((i = 1; i <= hosts; i++)); do nl_clear "$i"; done
    log "netlab: sheriff script '$stop_script'"
    sheriff -s "$stop_script" --wait-timeout "$wait_timeout" 2>&1 | tee "$logdir/sheriff_$stop_script.log" || rc=1
  fi
  [[ $rc -eq 0 ]] && log "netlab: done" || log "netlab: a sheriff script failed"
  return $rc
}

# netlab_cleanup: stops the deputies (they stop their commands) and removes the namespaces.
netlab_cleanup() {
  trap - EXIT INT TERM
  local p
  for p in "${NL_DEPUTIES[@]}"; do kill -TERM "$p" 2>/dev/null || true; done
  for p in "${NL_DEPUTIES[@]}"; do wait "$p" 2>/dev/null || true; done
  nl_teardown "$NL_HOSTS"
  log "netlab: namespaces removed; logs in $NL_LOGDIR"
}

# nl_sleep SEC: a sleep that Ctrl-C interrupts at once (traps run when `wait` returns).
nl_sleep() {
  sleep "$1" &
  wait $! || true
}

# netlab_follow_schedule SPEC DURATION: carries out the timed link events.
netlab_follow_schedule() {
  local spec=$1 duration=$2 start now ev t action host arg last=0
  local -a events=()
  IFS=';' read -ra events <<<"$spec"
  for ev in "${events[@]}"; do
    read -r t _ <<<"$ev"
    [[ -n "$t" ]] && last=$(awk -v a="$last" -v b="$t" 'BEGIN{print (b>a)?b:a}')
  done
  [[ -n "$duration" ]] || duration=$(awk -v l="$last" 'BEGIN{print (l+3>3)?l+3:3}')
  start=$(date +%s.%N)
  for ev in "${events[@]}"; do
    read -r t action host arg <<<"$ev"
    [[ -z "$t" ]] && continue
    [[ "$action" == script || "$host" =~ ^[0-9]+$ ]] || die "netlab: bad schedule event '$ev' (host number expected)"
    now=$(date +%s.%N)
    nl_sleep "$(awk -v s="$start" -v t="$t" -v n="$now" 'BEGIN{d=s+t-n; print (d>0)?d:0}')"
    case "$action" in
      cut) log "t=${t}s: cut host $host"; nl_link "$host" down ;;
      restore) log "t=${t}s: restore host $host"; nl_link "$host" up ;;
      loss) log "t=${t}s: ${arg}% loss on host $host"; nl_loss "$host" "${arg:?loss needs a percent}" ;;
      clear) log "t=${t}s: clear host $host"; nl_clear "$host" ;;
      script) log "t=${t}s: sheriff script '$host'"
              sheriff -s "$host" --wait-timeout "$NL_WAIT_TIMEOUT" 2>&1 | tee -a "$NL_LOGDIR/sheriff_events.log" ||
                log "netlab: script '$host' failed" ;;
      crash) log "t=${t}s: crash '$arg' on host $host"; nl_crash "$host" "${arg:?crash needs a text}" ;;
      *) die "netlab: unknown schedule action '$action' in '$ev'" ;;
    esac
  done
  now=$(date +%s.%N)
  nl_sleep "$(awk -v s="$start" -v t="$duration" -v n="$now" 'BEGIN{d=s+t-n; print (d>0)?d:0}')"
}
