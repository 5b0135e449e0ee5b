# help: three simulated robots through the whole stack in network namespaces; writes a report
source "$SLIDE_ROOT/tools/commands/lib/team_run.sh"

demo_usage() {
  cat <<USAGE
usage: ./slide demo [--world forest|urban|indoor] [--robots N] [--seed S] [--distance M]
                    [--overlap F] [--rate R] [--settle SEC] [--out DIR]
                    [--perception label-free|emulated|oracle] [--data SIM_DIR]
                    [--sensors lidar,rgbd,...] [--aerial-robots IDS] [--view-port P | --no-view] [--force]
Simulates a team mission (default: 3 robots, forest, each in its own unknown odometry frame),
then runs every robot's daemons (sensor driver, segmenter, tracker, optimizer, loop closer,
peer sync) under its own slide-deputy in its own network namespace (./slide netlab), driven by
slide-sheriff, with the team links cut and restored on a schedule so robots meet
intermittently. Robot and team buses are recorded with lcm-logger; slide-demo-report then
writes report.md with the merged map of each robot as pictures, inter-robot transform errors,
ATE, object precision/recall and bandwidth. Needs root (network namespaces).
--data reuses a mission that slide-sim (or an earlier demo: RUN/data) wrote, instead of simulating
one; --world, --robots, --seed, --distance and --overlap then come from it.
--overlap is the fraction of each robot's path shared with the others (slide-sim).
--perception: label-free (default: the drivers publish raw data only, LiDAR robots segment
geometrically), emulated (the drivers publish the detection emulator's RangeNet++-class labels /
YOLOv8-seg-class masks, made from ground truth inside the driver) or oracle (the simulator's
ground-truth labels reach the robots: an upper bound, and the report says so).
--sensors gives each robot its sensor (a mixed team, e.g. lidar,rgbd,rgbd; default all lidar);
an RGBD robot in a label-free run takes the detection emulator's masks, as it would a detector's.
--aerial-robots lists the robots that fly (e.g. 2), the others drive.
While the team runs, slide-viewer follows the run's logs and serves the live map at
http://127.0.0.1:<view-port>/ (default 8080; over SSH: ssh -L 8080:127.0.0.1:8080 <this host>);
the report gets its pictures of each robot's view. --no-view runs without it. Afterwards
./slide view RUN_DIR replays the run in the browser.
An --out folder that holds an earlier run (state/ or logs/) is refused: its daemons would resume
the earlier run's journals. --force deletes that run's state, logs, outputs and report first.
Defaults: --world forest --robots 3 --seed 1 --distance 150 --overlap 0.6 --rate 1 --settle 25
          --out runs/demo-<time> --perception label-free
USAGE
}

main() {
  if wants_help "$@"; then demo_usage; return 0; fi
  local world=forest robots=3 seed=1 distance=150 overlap=0.6 rate=1 settle=25 out="" perception=label-free reuse= sensors="" aerial="" view_port=8080 force=
  while [[ $# -gt 0 ]]; do
    case "$1" in
      --world) world=$2; shift 2 ;;
      --robots) robots=$2; shift 2 ;;
      --seed) seed=$2; shift 2 ;;
      --distance) distance=$2; shift 2 ;;
      --overlap) overlap=$2; shift 2 ;;
      --rate) rate=$2; shift 2 ;;
      --settle) settle=$2; shift 2 ;;
      --out) out=$2; shift 2 ;;
      --perception) perception=$2; shift 2 ;;
      --data) reuse=$2; shift 2 ;;
      --sensors) sensors=$2; shift 2 ;;
      --aerial-robots) aerial=$2; shift 2 ;;
      --view-port) view_port=$2; shift 2 ;;
      --no-view) view_port=""; shift ;;
      --force) force=1; shift ;;
      *) die "demo: unknown option '$1' (see ./slide demo --help)" ;;
    esac
  done
  [[ "$robots" =~ ^[1-9]$ ]] || die "demo: --robots must be 1..9 (got '$robots')"
  team_run_perception "$perception" > /dev/null || die "demo: --perception must be label-free, emulated or oracle (got '$perception')"
  [[ $(id -u) -eq 0 ]] || die "demo needs root: it runs each robot in its own network namespace"
  [[ -n "${SLIDE_NO_BUILD:-}" ]] || ensure_built
  out=${out:-$SLIDE_ROOT/runs/demo-$(date +%Y%m%d-%H%M%S)}
  if [[ -d "$out/state" || -d "$out/logs" ]]; then
    [[ -n "$force" ]] || die "demo: $out holds an earlier run (state/, logs/): its optimizers would resume that run's journals; choose another --out, or --force to delete that run first"
    rm -rf "$out/state" "$out/logs" "$out/out" "$out/report" "$out/config" "$out/keys" "$out/team.pmd" "$out/netlab.log" "$out/viewer.log"
  fi
  mkdir -p "$out"
  out=$(cd "$out" && pwd)
  local data="$out/data" t0=$SECONDS
  export PATH="$SLIDE_BIN:$PATH"

  if [[ -n "$reuse" ]]; then
    [[ -f "$reuse/objects.csv" && -d "$reuse/robot0" ]] || die "demo: --data $reuse is not a simulated mission (no objects.csv or robot0/)"
    robots=$(find "$reuse/" -maxdepth 1 -name 'robot[0-9]' -type d | wc -l)  # "/": RUN/data of a reused run is a link
    log "1/3 reusing the $robots-robot mission in $reuse"
    ln -sfn "$(cd "$reuse" && pwd)" "$data"
  else
    local team=() sim_team
    [[ -z "$sensors" ]] || team+=(--sensors "$sensors")
    [[ -z "$aerial" ]] || team+=(--aerial-robots "$aerial")
    sim_team=${sensors:+ ($sensors)}${aerial:+, aerial: $aerial}
    log "1/3 simulating a $robots-robot $world mission$sim_team ($distance m each, seed $seed) into $data"
    slide-sim --world "$world" --robots "$robots" --seed "$seed" --distance "$distance" --overlap "$overlap" --rate 5 \
      "${team[@]}" --out "$data" || die "demo: simulation failed"
  fi

  # Mission length from robot 0's odometry (one line per frame, first column its time).
  local frames mission
  frames=$(wc -l < "$data/robot0/odom.txt")
  mission=$(awk -v f="$frames" -v r="$rate" -v d="$(head -2 "$data/robot0/odom.txt" | awk 'NR==1{a=$1} NR==2{print $1-a}')" \
    'BEGIN { printf "%d", (f * d) / (r > 0 ? r : 1) + 1 }')
  local duration=$((mission + settle))
  team_run_write_config "$out" "$data" "$robots" "$rate" "$perception" || die "demo: cannot write the run's configuration in $out/config"
  [[ "$perception" != oracle ]] || log "ORACLE run: ground-truth labels reach the robots; its figures are an upper bound"
  local viewer_pid=""
  if [[ -n "$view_port" ]]; then
    # On the host network: it follows the logs the robots' loggers write inside their namespaces.
    slide-viewer --replay "$out" --follow --port "$view_port" > "$out/viewer.log" 2>&1 &
    viewer_pid=$!
    sleep 1
    if kill -0 "$viewer_pid" 2> /dev/null; then
      log "watch it live: http://127.0.0.1:$view_port/  (from another machine: ssh -L $view_port:127.0.0.1:$view_port $(hostname))"
    else
      log "the viewer did not start (port $view_port taken? see $out/viewer.log); the demo goes on without it"
      viewer_pid=""
    fi
  fi
  log "2/3 running the team: $frames frames per robot, ~${mission}s of data at ${rate}x, then ${settle}s to settle"
  "$SLIDE_ROOT/slide" netlab --hosts "$robots" --config "$out/team.pmd" \
    --schedule "$(team_run_schedule "$robots" "$mission")" --duration "$duration" --wait-timeout 60 \
    > "$out/netlab.log" 2>&1 || { [[ -z "$viewer_pid" ]] || kill "$viewer_pid"; die "demo: the team run failed; see $out/netlab.log"; }
  local shots=""
  if [[ -n "$viewer_pid" ]]; then
    mkdir -p "$out/report"
    shots=$(node "$SLIDE_ROOT/daemons/viewer/web/screenshot.mjs" "http://127.0.0.1:$view_port/" "$out/report/viewer" 30 \
      2>> "$out/viewer.log") || log "no viewer pictures (see $out/viewer.log)"
    kill "$viewer_pid" 2> /dev/null || true
    wait "$viewer_pid" 2> /dev/null || true
  fi

  log "3/3 evaluating against ground truth"
  local ids
  ids=$(seq -s, 0 $((robots - 1)))
  slide-demo-report --run "$out" --data "$data" --robots "$ids" --wall-s $((SECONDS - t0)) --perception "$perception" ||
    die "demo: evaluation failed"
  if [[ -n "$shots" ]]; then
    {
      echo
      echo "## Live viewer"
      echo "Each robot's view at the end of the run (slide-viewer; replay with \`./slide view $out\`)."
      local f
      for f in $shots; do echo; echo "![$(basename "$f" .png)]($(basename "$f"))"; done
    } >> "$out/report/report.md"
  fi
  log "report: $out/report/report.md (pictures beside it); replay in the browser: ./slide view $out"
}
