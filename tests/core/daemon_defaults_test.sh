#!/usr/bin/env bash
# ctest: every daemon started with only --robot 2 listens on robot 2's own bus (port 7669), as
# README says, and peer sync keeps its journal outside /tmp. Runs each daemon for a moment in
# a private network namespace. Usage: daemon_defaults_test.sh BUILD
set -uo pipefail
bin=$1/bin
if [[ $(id -u) -ne 0 ]] || ! unshare -n true 2>/dev/null; then echo "skipped: needs root for a network namespace"; exit 77; fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
want="udpm://239.255.76.67:7669?ttl=0&recv_buf_size=4194304"  # recv_buf_size: a scan burst fits
"$bin/slide-team-keys" --team 0,1,2 --out "$tmp/keys" >/dev/null 2>&1 || { echo "FAILED: slide-team-keys"; exit 1; }
keys=$tmp/keys/robot2.keys
fail=0
run() {  # name, then the command line
  local name=$1
  shift
  unshare -n bash -c 'ip link set lo up; ip route add 224.0.0.0/4 dev lo; timeout -s INT 2 "$@"' _ "$@" >"$tmp/$name.log" 2>&1
  if grep -qF "$want" "$tmp/$name.log"; then echo "ok: $name on $want"
  else echo "FAILED: $name does not use robot 2's bus:"; cat "$tmp/$name.log"; fail=1; fi
}
run segmenter "$bin/slide-segmenter" --robot 2
run tracker "$bin/slide-tracker" --robot 2
run optimizer "$bin/slide-optimizer" --robot 2 --journal "$tmp/opt.journal"
run loop-closer "$bin/slide-loop-closer" --robot 2
run peer-sync "$bin/slide-peer-sync" --robot 2 --state-dir "$tmp/ps" --team-key-file "$keys"
# Peer sync's default journal folder survives reboots: for a user, ~/.local/state/slide (the
# root default, /var/lib/slide, is not written by a test).
mkdir -p "$tmp/home" && chmod 777 "$tmp" "$tmp/home" && chmod 755 "$tmp/keys" && chown 65534 "$keys"
unshare -n bash -c 'ip link set lo up; ip route add 224.0.0.0/4 dev lo
  exec setpriv --reuid=65534 --regid=65534 --clear-groups env HOME="$0" XDG_STATE_HOME= timeout -s INT 2 "$@"' \
  "$tmp/home" "$bin/slide-peer-sync" --robot 2 --team-key-file "$keys" >"$tmp/ps-default.log" 2>&1
if grep -qF "journal $tmp/home/.local/state/slide/peer-sync/robot2 " "$tmp/ps-default.log"; then echo "ok: peer sync journal under ~/.local/state/slide"
else echo "FAILED: peer sync's default journal:"; cat "$tmp/ps-default.log"; fail=1; fi
exit $fail
