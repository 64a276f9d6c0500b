#!/usr/bin/env bash
# Runs that take longer than one sitting (the R = 20 packings, the f = 100 crumpling
# deck) continue across sittings and machines. Each run is a folder outside the
# repository (run data does not go into git):
#
#   $SLENDER_RUNS/<name>/   (or --dir DIR; default ../slender-runs next to the repository)
#     run.conf              the deck and its -v variables (written by `init`)
#     restart.h5, traj/     the newest checkpoint and the trajectory segments (HDF5)
#     thermo.csv, log/      thermo rows from step 0, each segment's console (head and tail)
#     segments.csv          steps, wall time and node-steps of each segment
#     result.json, finished the deck's RESULT line, once it ended by itself
#
#   scripts/long_run.sh [--dir DIR] init <name> DECK [-v k=v ...]   create a run of a
#                              deck under examples/ (e.g. examples/pack3d/low_torsion.lua)
#   scripts/long_run.sh [--dir DIR] start <name>   run (or continue) it in the work folder
#                              $SLENDER_WORK/<name> (default /tmp/slender-work), in the
#                              foreground: start it with nohup/setsid for a long run
#   scripts/long_run.sh [--dir DIR] save <name>    copy the newest checkpoint, thermo CSV,
#                              trajectory segments and logs back into the run's folder
#   scripts/long_run.sh [--dir DIR] status [name]  steps and the last thermo row of each run
#
# The binary and the decks are copied into the work folder when a run starts, so a
# rebuild or an edited deck does not change a run that is going on. The finished runs of
# the thesis studies are recorded in docs/results/long_runs/ (configuration, results,
# segment timings); `init <name>` with no DECK takes a recorded run's run.conf from there.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
runs_dir="${SLENDER_RUNS:-$(dirname "$root")/slender-runs}"
work_root="${SLENDER_WORK:-/tmp/slender-work}"
records="$root/docs/results/long_runs"

usage() {
  sed -n '2,25p' "$0" | sed 's/^# \{0,1\}//'
  exit 2
}

conf_of() {
  local conf="$runs_dir/$1/run.conf"
  [[ -f "$conf" ]] || { echo "long_run: no $conf (runs in $runs_dir: $(ls "$runs_dir" 2>/dev/null | tr '\n' ' '); 'init $1 DECK' creates it)" >&2; exit 2; }
  # run.conf sets DECK (path from the repository root), OUT (the deck's output name)
  # and ARGS (the -v variables, the same for every segment of the run)
  DECK="" OUT="" ARGS=""
  # shellcheck disable=SC1090
  source "$conf"
  [[ -n "$DECK" && -n "$OUT" ]] || { echo "long_run: $conf must set DECK and OUT" >&2; exit 2; }
}

# init <name> DECK [-v k=v ...]: a new run; without DECK, a run recorded in
# docs/results/long_runs/<name>/run.conf (to run it again from step 0)
init() {
  local name="$1" store="$runs_dir/$1"
  shift
  [[ -f "$store/run.conf" ]] && { echo "long_run: $store/run.conf exists" >&2; exit 1; }
  mkdir -p "$store"
  if [[ $# -eq 0 ]]; then
    [[ -f "$records/$name/run.conf" ]] || { echo "long_run: give a DECK (no recorded run $records/$name)" >&2; exit 2; }
    cp "$records/$name/run.conf" "$store/run.conf"
  else
    local deck="$1" out
    shift
    deck="examples/${deck#examples/}"
    [[ -f "$root/$deck" ]] || { echo "long_run: no deck $root/$deck" >&2; rmdir "$store" 2>/dev/null; exit 2; }
    out="$(basename "$deck" .lua)"
    { echo "# $name: created $(date -u +%F)"
      echo "DECK=$deck"
      echo "OUT=$out"
      echo "ARGS=\"$*\""; } > "$store/run.conf"
  fi
  echo "long_run: $store/run.conf:"
  cat "$store/run.conf"
}

start() {
  local name="$1" store="$runs_dir/$1" work="$work_root/$1"
  conf_of "$name"
  if [[ -f "$store/finished" ]]; then
    echo "long_run: $name has finished ($(cat "$store/finished")); remove $store/finished to run it again" >&2
    exit 1
  fi
  mkdir -p "$work/bin" "$work/log"
  # SLENDER_BIN: another binary (the tests use a stand-in); its libslender.so, if any,
  # goes with it
  local bin="${SLENDER_BIN:-$root/build/slender}"
  cp "$bin" "$work/bin/slender"
  [[ -f "$(dirname "$bin")/libslender.so" ]] && cp "$(dirname "$bin")/libslender.so" "$work/bin/"
  rm -rf "$work/examples" && cp -r "$root/examples" "$work/examples"
  cd "$work"
  local restart=()
  if [[ ! -f "${OUT}_restart.h5" && -f "$store/restart.h5" ]]; then
    # a fresh machine: take the stored state
    cp "$store/restart.h5" "${OUT}_restart.h5"
    [[ -f "$store/thermo.csv" ]] && cp "$store/thermo.csv" "${OUT}_thermo.csv"
    if [[ -d "$store/traj" ]]; then cp "$store"/traj/*.h5 . 2>/dev/null || true; fi
  fi
  [[ -f "${OUT}_restart.h5" ]] && restart=(-v "restart=${OUT}_restart.h5")
  local log
  log="log/$(date +%Y%m%d-%H%M%S)-$$.txt"
  echo "long_run: $name in $work: bin/slender examples/${DECK#examples/} $ARGS ${restart[*]:-} > $log"
  # shellcheck disable=SC2086
  local rc=0
  LD_LIBRARY_PATH="$work/bin" ./bin/slender "examples/${DECK#examples/}" $ARGS ${restart[@]+"${restart[@]}"} > "$log" 2>&1 || rc=$?
  # a run that ends by itself (jammed, max_phi, max_steps) is finished; its summary
  # is the deck's last `RESULT key=value ...` line (slender.result), kept as JSON
  if [[ $rc -eq 0 ]]; then
    grep '^RESULT ' "$log" | tail -1 | awk '{
      printf "{"
      for (i = 2; i <= NF; ++i) {
        k = $i; sub(/=.*/, "", k); v = substr($i, length(k) + 2)
        if (v !~ /^[-+]?([0-9]+[.]?[0-9]*|[.][0-9]+)([eE][-+]?[0-9]+)?$/) v = "\"" v "\""
        printf "%s\"%s\": %s", (i > 2 ? ", " : ""), k, v
      }
      print "}" }' > result.json
    echo "$(date -u +%F) $(tail -c 300 result.json)" > finished
  fi
  return $rc
}

save() {
  local name="$1" store="$runs_dir/$1" work="$work_root/$1"
  conf_of "$name"
  [[ -d "$work" ]] || { echo "long_run: nothing to save, no $work" >&2; exit 1; }
  mkdir -p "$store/traj"
  [[ -f "$work/${OUT}_restart.h5" ]] && cp "$work/${OUT}_restart.h5" "$store/restart.h5"
  [[ -f "$work/${OUT}_thermo.csv" ]] && cp "$work/${OUT}_thermo.csv" "$store/thermo.csv"
  local f
  for f in "$work/${OUT}".h5 "$work/${OUT}"_[0-9]*.h5; do
    [[ -f "$f" ]] && cp "$f" "$store/traj/"
  done
  [[ -f "$work/result.json" ]] && cp "$work/result.json" "$store/result.json"
  [[ -f "$work/finished" ]] && cp "$work/finished" "$store/finished"
  # the logs carry the stability guard's messages and the wall times; their thermo
  # echo repeats thermo.csv, so keep only the head (setup report) and the tail
  mkdir -p "$store/log"
  for f in "$work"/log/*.txt; do
    [[ -f "$f" ]] || continue
    { head -n 12 "$f"; echo "[... thermo rows, see thermo.csv ...]"; tail -n 40 "$f"; } > "$store/log/$(basename "$f")"
  done
  segments "$store" "$work"
  du -sh "$store"
}

# segments.csv: one row per segment (one machine's sitting), from its log: the steps
# it ran, its wall time (log name to last write; other jobs may have shared the
# machine) and node-steps from the thermo rows, so a run's total cost adds up
# across sessions. Rows of earlier segments, stored before, are kept.
segments() {
  local store="$1" work="$2" csv="$2/${OUT}_thermo.csv" out="$1/segments.csv" f
  [[ -f "$csv" ]] || return 0
  local tmp
  tmp="$(mktemp)"
  [[ -f "$out" ]] && tail -n +2 "$out" > "$tmp"
  for f in "$work"/log/*.txt; do
    [[ -f "$f" ]] || continue
    local seg first last t0 t1
    seg="$(basename "$f" .txt)"
    # the console prints steps as %.7g (1.301e+07)
    first="$(awk '$1 ~ /^[0-9]+(\.[0-9]+)?(e\+[0-9]+)?$/ { printf "%d", $1; exit }' "$f")"
    last="$(awk '$1 ~ /^[0-9]+(\.[0-9]+)?(e\+[0-9]+)?$/ { s = $1 } END { if (s != "") printf "%d", s }' "$f")"
    [[ -n "$first" && -n "$last" ]] || continue
    t0="$(date -d "${seg:0:4}-${seg:4:2}-${seg:6:2} ${seg:9:2}:${seg:11:2}:${seg:13:2}" +%s)"
    t1="$(stat -c %Y "$f")"
    local ns
    ns="$(awk -F, -v a="$first" -v b="$last" '
      NR == 1 { for (i = 1; i <= NF; ++i) if ($i == "count.nodes") c = i; next }
      $1 + 0 <= a { prev = $1 + 0; next }
      $1 + 0 <= b { n += $c * ($1 - prev); prev = $1 + 0 }
      END { printf "%.0f", n }' "$csv")"
    grep -v "^$seg," "$tmp" > "$tmp.2" || true
    mv "$tmp.2" "$tmp"
    awk -v s="$seg" -v a="$first" -v b="$last" -v w="$((t1 - t0))" -v n="$ns" \
      'BEGIN { printf "%s,%s,%s,%d,%s,%.3g\n", s, a, b, w, n, (w > 0 ? n / w : 0) }' >> "$tmp"
  done
  { echo "segment,start_step,end_step,wall_s,node_steps,node_steps_per_s"; sort "$tmp"; } > "$out"
  rm -f "$tmp"
}

status() {
  local d name
  [[ -d "$runs_dir" ]] || { echo "long_run: no runs in $runs_dir"; return 0; }
  for d in "$runs_dir"/*/; do
    name="$(basename "$d")"
    [[ $# -gt 0 && "$1" != "$name" ]] && continue
    [[ -f "$d/run.conf" ]] || continue  # not a deck run (a sweep's folder, say)
    conf_of "$name"
    local csv="$work_root/$name/${OUT}_thermo.csv"
    [[ -f "$csv" ]] || csv="$d/thermo.csv"
    if [[ -f "$d/finished" ]]; then
      echo "$name: finished $(cat "$d/finished")"
    elif [[ -f "$csv" ]]; then
      awk -F, -v n="$name" 'NR == 1 { for (i = 1; i <= NF; ++i) c[$i] = i; next }
        { last = $0 } END { split(last, v, ",")
          printf "%s: step %d, phi %.4f, force (averaged) %.4g, %d nodes\n", n, v[1],
                 v[c["feed.phi"]], v[c["feed.force_avg"]], v[c["count.nodes"]] }' "$csv"
    else
      echo "$name: not started"
    fi
  done
}

if [[ "${1:-}" == --dir || "${1:-}" == -d ]]; then
  [[ $# -ge 2 ]] || usage
  runs_dir="$2"
  shift 2
fi
[[ "${1:-}" == -h || "${1:-}" == --help ]] && { sed -n '2,25p' "$0" | sed 's/^# \{0,1\}//'; exit 0; }
[[ $# -ge 1 ]] || usage
# a relative --dir or $SLENDER_RUNS is taken from where the script was called
[[ "$runs_dir" = /* ]] || runs_dir="$PWD/$runs_dir"
case "$1" in
  init) [[ $# -ge 2 ]] || usage; shift; init "$@" ;;
  start) [[ $# -eq 2 ]] || usage; start "$2" ;;
  save) [[ $# -eq 2 ]] || usage; save "$2" ;;
  status) shift; status "$@" ;;
  *) usage ;;
esac
