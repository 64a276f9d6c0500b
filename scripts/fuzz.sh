#!/usr/bin/env bash
# Runs one libFuzzer target for a given amount of CPU time (not wall time: on a shared
# machine at low priority a wall-clock limit says little) and reports executions, coverage
# and findings. The target's seed corpus is copied, so tests/fuzz/corpus stays as committed;
# a finding is left in OUT/artifacts (add it to the corpus once fixed).
#   cmake --preset fuzz && cmake --build --preset fuzz -j 2
#   scripts/fuzz.sh checkpoint 3600 /tmp/fuzz-checkpoint     # targets: deck_table, mesh, checkpoint
set -euo pipefail
cd "$(dirname "$0")/.."
target=${1:?target: deck_table, mesh or checkpoint}
cpu_limit=${2:-3600}
out=${3:-/tmp/slender-fuzz-$target}
bin=$PWD/build-fuzz/tests/fuzz/fuzz_$target
[ -x "$bin" ] || { echo "fuzz.sh: $bin missing: cmake --preset fuzz && cmake --build --preset fuzz" >&2; exit 1; }
mkdir -p "$out/corpus" "$out/artifacts"
cp -n tests/fuzz/corpus/"$target"/* "$out/corpus/" 2>/dev/null || true
cd "$out"
# With autogroup scheduling (Linux's default for desktop and container kernels) nice only
# orders processes within one session: a fuzzer started with setsid would still take a
# full share beside a build. Lowering the session's own group makes it yield for real;
# done only when this script leads its own session (setsid), so no caller is slowed.
if [ -w /proc/self/autogroup ] && [ "$(ps -o sid= -p $$ | tr -d ' ')" = "$$" ]; then echo "${FUZZ_NICE:-10}" >/proc/self/autogroup 2>/dev/null || true; fi
nice -n "${FUZZ_NICE:-10}" "$bin" -timeout=30 -rss_limit_mb=4096 -artifact_prefix="$out/artifacts/" \
  -print_final_stats=1 corpus >"$out/fuzz.log" 2>&1 &
pid=$!
cpu=0
tick=$(getconf CLK_TCK)
while kill -0 "$pid" 2>/dev/null; do
  sleep 5
  # utime + stime of the fuzzer (fields 14 and 15 of /proc/PID/stat; after the ")" that
  # ends the command name they are the 12th and 13th), in seconds
  if stat=$(cat /proc/"$pid"/stat 2>/dev/null); then
    cpu=$(awk -v t="$tick" '{print int(($12 + $13) / t)}' <<<"${stat##*) }")
  fi
  if [ "$cpu" -ge "$cpu_limit" ]; then kill -INT "$pid"; break; fi
done
wait "$pid" && rc=0 || rc=$?
# A timeout or slow unit is measured in wall time: a fuzzer at low priority on a busy machine
# can be starved past the limit by an input that takes a second. Each is run again here at
# normal priority; one that passes within the limit is moved to starved/ and not counted.
mkdir -p starved
for a in artifacts/timeout-* artifacts/slow-unit-*; do
  [ -e "$a" ] || continue
  t0=$(date +%s.%N)
  if timeout 30 "$bin" "$a" >/dev/null 2>&1; then
    t=$(awk -v a="$t0" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }')
    echo "fuzz.sh: $a runs in $t s at normal priority: starved, not a finding"
    mv "$a" starved/
  fi
done
execs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' fuzz.log | grep -o '[0-9]*$' || echo "?")
cov=$(grep -o 'cov: [0-9]*' fuzz.log | tail -1 | grep -o '[0-9]*$' || echo "?")
findings=$(find artifacts -type f | wc -l)
echo "fuzz $target: $cpu CPU-s, $execs executions, coverage $cov, $findings finding(s)," \
  "exit $rc (0 or 72 after the CPU limit: clean); log $out/fuzz.log"
[ "$findings" -eq 0 ]
