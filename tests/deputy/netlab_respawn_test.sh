#!/usr/bin/env bash
# ctest (scenario): ./slide netlab, host 2 cut off from the sheriff while its worker is
# killed; the deputy must respawn it on its own (new pid, same run id) and the team must be
# back in full after the link is restored. Usage: netlab_respawn_test.sh SRC BUILD
set -euo pipefail
src=$1 build=$2
if [[ $(id -u) -ne 0 ]]; then echo "skipped: needs root"; exit 77; fi
out=$(mktemp)
trap 'rm -f "$out"' EXIT
SLIDE_BUILD=$build "$src/slide" netlab --config "$src/tests/deputy/fixtures/netlab_quick.pmd" \
  --schedule "1 cut 2; 2 crash 2 sleep 120; 4 restore 2" --duration 6 --wait-timeout 10 >"$out" 2>&1 || { cat "$out"; exit 1; }
cat "$out"
fail() { echo "FAILED: $*"; exit 1; }
pid_of() { awk -v d="$1" '$1 == d && $2 == "worker" { print $5 }' <<<"$2" | head -1; }
started=$(sed -n "/sheriff script 'start'/,/script 'start' done/p" "$out")
status=$(sed -n '/netlab: status/,/sheriff script .stop./p' "$out")
grep -q "killed 1 process(es) matching 'sleep 120'" "$out" || fail "the crash event killed nothing"
p0=$(pid_of robot2 "$started") p1=$(pid_of robot2 "$status")
[[ -n "$p0" && -n "$p1" && "$p0" != "-" && "$p1" != "-" ]] || fail "robot2 worker not running (pids '$p0' '$p1')"
[[ "$p0" != "$p1" ]] || fail "robot2 worker was not respawned (pid $p0)"
grep -Eq 'robot2 +worker +robots +running +[0-9]+ +1 ' <<<"$status" || fail "robot2 worker not running with run id 1"
[[ $(grep -Ec 'robot[123] +worker +robots +running' <<<"$status") -eq 3 ]] || fail "not all three running after restore"
echo "netlab respawn test passed (robot2 worker pid $p0 -> $p1)"
