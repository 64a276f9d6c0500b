#!/usr/bin/env bash
# Runs that take longer than one sitting (the R = 20 packings, the f = 100 crumpling
# deck) continue across machines: runs/<name>/run.conf says which deck with which
# variables, and runs/<name>/ keeps the last checkpoint, the thermo CSV and the
# trajectory segments, so that a fresh clone can pick the run up where it stopped.
#
#   scripts/long_run.sh start <name>   run (or continue) it in $SLENDER_RUNS/<name>
#                                      (default /tmp/slender-runs); foreground, so
#                                      start it with nohup/setsid for a long run
#   scripts/long_run.sh save <name>    copy the newest checkpoint, thermo CSV and
#                                      trajectory segments back into runs/<name>/
#   scripts/long_run.sh status [name]  steps and the last thermo row of each run
#
# The binary and the decks are copied into the work folder when a run starts, so a
# rebuild or an edited deck does not change a run that is going on.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
runs_root="${SLENDER_RUNS:-/tmp/slender-runs}"

usage() {
  sed -n '2,14p' "$0" | sed 's/^# \{0,1\}//'
  exit 2
}

conf_of() {
  local conf="$root/runs/$1/run.conf"
  [[ -f "$conf" ]] || { echo "long_run: no $conf (known runs: $(ls "$root/runs" | grep -v README | tr '\n' ' '))" >&2; exit 2; }
  # run.conf sets DECK (path from the repository root), OUT (the deck's output name)
  # and ARGS (the -v variables, the same for every segment of the run)
  DECK="" OUT="" ARGS=""
  # shellcheck disable=SC1090
  source "$conf"
  [[ -n "$DECK" && -n "$OUT" ]] || { echo "long_run: $conf must set DECK and OUT" >&2; exit 2; }
}

start() {
  local name="$1" store="$root/runs/$1" work="$runs_root/$1"
  conf_of "$name"
  if [[ -f "$store/finished" ]]; then
    echo "long_run: $name has finished ($(cat "$store/finished")); remove runs/$name/finished to run it again" >&2
    exit 1
  fi
  mkdir -p "$work/bin" "$work/log"
  cp "$root/build/slender" "$root/build/libslender.so" "$work/bin/"
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
  log="log/$(date +%Y%m%d-%H%M%S).txt"
  echo "long_run: $name in $work: bin/slender examples/${DECK#examples/} $ARGS ${restart[*]:-} > $log"
  # shellcheck disable=SC2086
  local rc=0
  LD_LIBRARY_PATH="$work/bin" ./bin/slender "examples/${DECK#examples/}" $ARGS ${restart[@]+"${restart[@]}"} > "$log" 2>&1 || rc=$?
  # a run that ends by itself (jammed, max_phi, max_steps) is finished; the
  # result line is the deck's JSON summary
  if [[ $rc -eq 0 ]]; then
    grep '^{' "$log" | tail -1 > result.json || true
    echo "$(date -u +%F) $(tail -c 300 result.json)" > finished
  fi
  return $rc
}

save() {
  local name="$1" store="$root/runs/$1" work="$runs_root/$1"
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
  du -sh "$store"
}

status() {
  local d name
  for d in "$root"/runs/*/; do
    name="$(basename "$d")"
    [[ $# -gt 0 && "$1" != "$name" ]] && continue
    conf_of "$name"
    local csv="$runs_root/$name/${OUT}_thermo.csv"
    [[ -f "$csv" ]] || csv="$d/thermo.csv"
    if [[ -f "$d/finished" ]]; then
      echo "$name: finished $(cat "$d/finished")"
    elif [[ -f "$csv" ]]; then
      echo "$name: $(head -1 "$csv")"
      echo "$name: $(tail -1 "$csv")"
    else
      echo "$name: not started"
    fi
  done
}

[[ $# -ge 1 ]] || usage
case "$1" in
  start) [[ $# -eq 2 ]] || usage; start "$2" ;;
  save) [[ $# -eq 2 ]] || usage; save "$2" ;;
  status) shift; status "$@" ;;
  *) usage ;;
esac
