# Network-namespace helpers for ./slide netlab (sourced). Everything lives in namespaces named
# "$NL_PREFIX-*": a bridge namespace holding br0, a "base" namespace for the sheriff, and
# h1..hN for the robots; nothing is created in or attached to the host's own network.

# nl_setup N: creates the bridge namespace and N+1 host namespaces (base = index 0).
nl_setup() {
  local n=$1 i ns
  ip netns add "$NL_PREFIX-br"
  ip -n "$NL_PREFIX-br" link set lo up
  ip -n "$NL_PREFIX-br" link add br0 type bridge
  ip -n "$NL_PREFIX-br" link set br0 type bridge mcast_snooping 0  # flood multicast to every port
  ip -n "$NL_PREFIX-br" link set br0 up
  for ((i = 0; i <= n; i++)); do
    ns=$(nl_ns "$i")
    ip netns add "$ns"
    ip -n "$ns" link set lo up
    ip -n "$NL_PREFIX-br" link add "p$i" type veth peer name eth0 netns "$ns"
    ip -n "$NL_PREFIX-br" link set "p$i" master br0
    ip -n "$NL_PREFIX-br" link set "p$i" up
    ip -n "$ns" addr add "10.77.0.$((i + 10))/24" dev eth0
    ip -n "$ns" link set eth0 up
    ip -n "$ns" route add 224.0.0.0/4 dev eth0
  done
}

# nl_ns I: namespace name of host I (0 = base).
nl_ns() { if [[ $1 -eq 0 ]]; then echo "$NL_PREFIX-base"; else echo "$NL_PREFIX-h$1"; fi; }

# nl_link I up|down: connects or cuts host I at its bridge port.
nl_link() { ip -n "$NL_PREFIX-br" link set "p$1" "$2"; }

# nl_loss I PERCENT: random loss on host I's link, both directions. Uses tc netem when the
# kernel has it; otherwise flaps the link in 100 ms slots (down with probability PERCENT).
declare -gA NL_FLAPPER=()
nl_loss() {
  local i=$1 pct=$2
  nl_clear "$i"
  if ip netns exec "$(nl_ns "$i")" tc qdisc replace dev eth0 root netem loss "${pct}%" 2>/dev/null &&
     ip netns exec "$NL_PREFIX-br" tc qdisc replace dev "p$i" root netem loss "${pct}%" 2>/dev/null; then
    log "host $i: netem loss ${pct}%"
    return
  fi
  log "host $i: no netem in this kernel, emulating ${pct}% loss by link flapping (100 ms slots)"
  ( trap 'exit 0' TERM
    while :; do
      if (( RANDOM % 100 < pct )); then nl_link "$i" down; else nl_link "$i" up; fi
      sleep 0.1
    done ) &
  NL_FLAPPER[$i]=$!
}

# nl_clear I: removes loss emulation of host I and brings its link up.
nl_clear() {
  local i=$1
  if [[ -n "${NL_FLAPPER[$i]:-}" ]]; then
    kill "${NL_FLAPPER[$i]}" 2>/dev/null || true
    wait "${NL_FLAPPER[$i]}" 2>/dev/null || true
    unset "NL_FLAPPER[$i]"
  fi
  ip netns exec "$(nl_ns "$i")" tc qdisc del dev eth0 root 2>/dev/null || true
  ip netns exec "$NL_PREFIX-br" tc qdisc del dev "p$i" root 2>/dev/null || true
  nl_link "$i" up
}

# nl_teardown N: stops loss flappers and deletes every namespace (veths and bridge go with them).
nl_teardown() {
  local n=$1 i
  for i in "${!NL_FLAPPER[@]}"; do kill "${NL_FLAPPER[$i]}" 2>/dev/null || true; done
  for ((i = 0; i <= n; i++)); do ip netns del "$(nl_ns "$i")" 2>/dev/null || true; done
  ip netns del "$NL_PREFIX-br" 2>/dev/null || true
}

# nl_crash I TEXT: SIGKILLs the processes of host I whose command line contains TEXT (never
# the deputy itself), to show the deputy respawning them, links up or down.
nl_crash() {
  local i=$1 text=$2 pid cmdline hits=0
  for pid in $(ip netns pids "$(nl_ns "$i")"); do
    cmdline=$(tr '\0' ' ' <"/proc/$pid/cmdline" 2>/dev/null) || continue
    [[ "$cmdline" == *"$text"* && "$cmdline" != *slide-deputy* ]] || continue
    kill -KILL "$pid" 2>/dev/null && hits=$((hits + 1))
  done
  log "host $i: killed $hits process(es) matching '$text'"
}
