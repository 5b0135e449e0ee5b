#!/usr/bin/env bash
# ctest: peer sync keeps its journal, by default, in a folder that survives reboots (for a user,
# ~/.local/state/slide; the root default, /var/lib/slide, is not written by a test), never in
# /tmp. Runs it for a moment in a private network namespace. (That every daemon's --robot N
# alone puts it on robot N's bus is tests/app/test_daemon_buses.cpp.) Usage: daemon_defaults_test.sh BUILD
set -uo pipefail
bin=$1/bin
if [[ $(id -u) -ne 0 ]] || ! unshare -n true 2>/dev/null; then echo "skipped: needs root for a network namespace"; exit 77; fi
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
"$bin/slide-team-keys" --team 0,1,2 --out "$tmp/keys" >/dev/null 2>&1 || { echo "FAILED: slide-team-keys"; exit 1; }
keys=$tmp/keys/robot2.keys
mkdir -p "$tmp/home" && chmod 777 "$tmp" "$tmp/home" && chmod 755 "$tmp/keys" && chown 65534 "$keys"
unshare -n bash -c 'ip link set lo up; ip route add 224.0.0.0/4 dev lo
  exec setpriv --reuid=65534 --regid=65534 --clear-groups env HOME="$0" XDG_STATE_HOME= timeout -s INT 2 "$@"' \
  "$tmp/home" "$bin/slide-peer-sync" --robot 2 --team-key-file "$keys" >"$tmp/ps-default.log" 2>&1
if grep -qF "journal $tmp/home/.local/state/slide/peer-sync/robot2 " "$tmp/ps-default.log"; then echo "ok: peer sync journal under ~/.local/state/slide"
else echo "FAILED: peer sync's default journal:"; cat "$tmp/ps-default.log"; exit 1; fi
