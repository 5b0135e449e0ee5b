# help: run the benchmark suites (all, or those named) into one JSON file and a Markdown report
BENCH_KNOWN_SUITES=(frontend backend place team system sim)
# Suites that run suite programs with arguments; they may run long, so they run only when named
# (never in a plain `./slide bench`, nor in CI). A suite of several parts separates them with
# ';'; a part "LABEL: program args" has its figures' names prefixed with "LABEL." (the team bench
# names its figures the same whatever the team size).
declare -A BENCH_NAMED_SUITES=(
  [place_scale]="slide-bench-place --only scale"
  [backend_scale]="slide-bench-backend --keyposes 1000 --background-solves --final-seconds 30;
                   slide-bench-backend --keyposes 4000 --background-solves --final-seconds 30;
                   slide-bench-backend --keyposes 10000 --background-solves --final-seconds 30"
  [team_scale]="robots3: slide-bench-team --robots 3; robots5: slide-bench-team --robots 5;
                robots10: slide-bench-team --robots 10"
  [system_scale]="slide-bench-system --worlds forest-5robots,forest-400m --no-view"
)

bench_usage() {
  cat <<USAGE
usage: ./slide bench [SUITE...] [--json FILE] [--out DIR] [--timeout SECONDS]
Runs each benchmark suite program build/bin/slide-bench-SUITE with --json, one after the
other, then merges their figures into one JSON file and a Markdown report beside it (same
name, .md) with value, target, paper and pass/fail per figure and the wall times.
Without SUITE: ${BENCH_KNOWN_SUITES[*]}, plus any other slide-bench-* present.
Named only (the scale suite of long missions and big teams; each may run long):
  place_scale    place recognition on maps of 1,000, 10,000 and 30,000 objects (~30 min)
  backend_scale  the back-end at 1,000, 4,000 and 10,000 key poses on a route that returns to
                 its start, full solves in the background (~10 min)
  team_scale     peer sync with 3, 5 and 10 robots, 200 key poses each (~2 min)
  system_scale   the demo with 5 robots, and with 3 robots driving 400 m each (~12 min)
A suite whose program is missing is reported as missing; a suite that fails is reported with
its exit code and the run goes on. Exit status 0 only when every suite ran and succeeded.
  --out DIR       where suite JSON files and logs go (default: build/bench/<UTC time>,
                  with build/bench/latest pointing at it)
  --json FILE     merged JSON (default: DIR/bench.json); the report is FILE with .md
  --timeout S     stop a suite after S seconds (reported as failed, exit code 124);
                  default 1800, 0 for none
Environment: SLIDE_BENCH_BIN (where the suite programs are, default build/bin),
SLIDE_NO_BUILD=1 (do not build first).
USAGE
}

main() {
  if wants_help "$@"; then
    bench_usage
    return 0
  fi
  local suites=() json="" out="" timeout_s=1800
  while [[ $# -gt 0 ]]; do
    case "$1" in
      --json) [[ $# -ge 2 ]] || die "bench: --json needs a FILE"; json="$2"; shift 2 ;;
      --out) [[ $# -ge 2 ]] || die "bench: --out needs a DIR"; out="$2"; shift 2 ;;
      --timeout) [[ $# -ge 2 && "$2" =~ ^[0-9]+$ ]] || die "bench: --timeout needs whole seconds"; timeout_s="$2"; shift 2 ;;
      -*) die "bench: unknown option $1 (see ./slide bench --help)" ;;
      *) [[ "$1" =~ ^[A-Za-z0-9_]+$ ]] || die "bench: bad suite name '$1'"; suites+=("$1"); shift ;;
    esac
  done
  [[ -n "${SLIDE_NO_BUILD:-}" ]] || ensure_built
  local bench_bin="${SLIDE_BENCH_BIN:-$SLIDE_BIN}"
  local report_tool="$SLIDE_BIN/slide-benchmark-report"
  [[ -x "$report_tool" ]] || die "bench: $report_tool is not built (run ./slide setup)"

  if [[ ${#suites[@]} -eq 0 ]]; then
    suites=("${BENCH_KNOWN_SUITES[@]}")
    local exe name known
    for exe in "$bench_bin"/slide-bench-*; do
      [[ -x "$exe" ]] || continue
      name="${exe##*/slide-bench-}"
      known=0
      for s in "${suites[@]}"; do [[ "$s" == "$name" ]] && known=1; done
      [[ $known -eq 1 ]] || suites+=("$name")
    done
  fi

  local started stamp
  started=$(date -u +%Y-%m-%dT%H:%M:%SZ)
  stamp=$(date -u +%Y%m%d-%H%M%S)
  if [[ -z "$out" ]]; then
    out="$SLIDE_BUILD/bench/$stamp"
    mkdir -p "$out" && ln -sfn "$stamp" "$SLIDE_BUILD/bench/latest"
  fi
  mkdir -p "$out" || die "bench: cannot create $out"
  out=$(cd "$out" && pwd)
  [[ -n "$json" ]] || json="$out/bench.json"
  mkdir -p "$(dirname "$json")" || die "bench: cannot create the directory of $json"
  local md="${json%.json}.md"
  [[ "$md" != "$json" ]] || md="$json.md"
  local manifest="$out/manifest.tsv"
  : > "$manifest"

  local t_all t0 t1 code suite exe suite_json log
  t_all=$(date +%s%N)
  for suite in "${suites[@]}"; do
    exe="$bench_bin/slide-bench-$suite"
    # One part per program run: "LABEL|program args" (LABEL may be empty).
    local parts=("|slide-bench-$suite")
    if [[ -n "${BENCH_NAMED_SUITES[$suite]:-}" ]]; then
      parts=()
      local part label named
      IFS=';' read -r -a named <<< "$(tr '\n' ' ' <<< "${BENCH_NAMED_SUITES[$suite]}")"
      for part in "${named[@]}"; do
        label=""
        if [[ "$part" =~ ^[[:space:]]*([A-Za-z0-9_]+):(.*)$ ]]; then
          label="${BASH_REMATCH[1]}"
          part="${BASH_REMATCH[2]}"
        fi
        parts+=("$label|$part")
      done
    fi
    suite_json="$out/$suite.json"
    log="$out/$suite.log"
    rm -f "$suite_json" "$out/$suite".part*.json
    : > "$log"
    local missing="" p args
    for p in "${parts[@]}"; do
      read -r -a args <<< "${p#*|}"
      [[ -x "$bench_bin/${args[0]}" ]] || missing="$bench_bin/${args[0]}"
    done
    if [[ -n "$missing" ]]; then
      log "suite $suite: MISSING ($missing not found)"
      printf '%s\tmissing\t0\t\t\n' "$suite" >> "$manifest"
      continue
    fi
    t0=$(date +%s%N)
    # Line-buffered output so that the log keeps what a killed suite printed.
    local runner=()
    command -v stdbuf >/dev/null && runner=(stdbuf -oL -eL)
    [[ "$timeout_s" -gt 0 ]] && runner=(timeout "$timeout_s" "${runner[@]}")
    code=0
    local n=0 part_json part_code merge=()
    for p in "${parts[@]}"; do
      read -r -a args <<< "${p#*|}"
      exe="$bench_bin/${args[0]}"
      args=("${args[@]:1}")
      part_json="$suite_json"
      if [[ ${#parts[@]} -gt 1 ]]; then
        n=$((n + 1))
        part_json="$out/$suite.part$n.json"
        merge+=("${p%%|*}=$part_json")
      fi
      log "suite $suite: running $exe ${args[*]} --json $part_json"
      set +e
      "${runner[@]}" "$exe" "${args[@]}" --json "$part_json" 2>&1 | tee -a "$log"
      part_code=${PIPESTATUS[0]}
      set -e
      [[ $code -ne 0 ]] || code=$part_code
    done
    # Several parts: one suite file, each part's figures named after its label.
    if [[ ${#merge[@]} -gt 0 ]]; then
      python3 - "$suite_json" "$suite" "${merge[@]}" <<'PY' || { log "suite $suite: its parts' JSON could not be merged"; [[ $code -ne 0 ]] || code=1; }
import json, os, sys
out, suite, results = sys.argv[1], sys.argv[2], []
for part in sys.argv[3:]:
    label, path = part.split("=", 1)
    if not os.path.exists(path):
        continue
    with open(path) as f:
        for r in json.load(f)["results"]:
            if label:
                r["name"] = label + "." + r["name"]
            results.append(r)
with open(out, "w") as f:
    json.dump({"suite": suite, "results": results}, f, indent=2)
    f.write("\n")
PY
    fi
    t1=$(date +%s%N)
    [[ $code -eq 0 ]] || log "suite $suite: FAILED with exit code $code (log: $log)"
    printf '%s\t%s\t%s\t%s\t%s\n' "$suite" "$code" "$(((t1 - t0) / 1000000))" "$suite_json" "$log" >> "$manifest"
  done
  local total_ms=$((($(date +%s%N) - t_all) / 1000000))
  local total_s
  total_s=$(printf '%d.%03d' $((total_ms / 1000)) $((total_ms % 1000)))
  "$report_tool" --manifest "$manifest" --json "$json" --markdown "$md" --total-wall-s "$total_s" \
    --started "$started" --host "$(hostname)" --command "./slide bench ${suites[*]}"
}
