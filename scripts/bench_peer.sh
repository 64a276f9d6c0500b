#!/usr/bin/env bash
# Speed against the peer: a bead-chain wire in a rigid cavity (2D circle or 3D sphere),
# slender against LAMMPS at the same N, start configuration (../shared/peers/gen_chain.py),
# dt and steps, run one after the other on this machine; slender also with each thread
# count of --threads. Prints node-steps/s of each and the ratios. A benchmark, not a test.
# Needs LAMMPS (Debian package lammps; installed if missing and we are root; --no-peer
# times slender alone).
#   scripts/bench_peer.sh [--dim 2|3] [--threads "1 2"] [--no-peer] [N ...]
#   (default: --dim 2 --threads 1, N = 10000 50000)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
peers="${PEERS:-$root/../shared/peers}"
slender="${SLENDER:-$root/build/slender}"
dim=2
threads="1"
peer=1
sizes=()
while [ $# -gt 0 ]; do
  case "$1" in
    --dim) dim="$2"; shift 2 ;;
    --threads) threads="$2"; shift 2 ;;
    --no-peer) peer=0; shift ;;
    -h|--help) sed -n '2,9p' "$0"; exit 0 ;;
    *) sizes+=("$1"); shift ;;
  esac
done
[ ${#sizes[@]} -gt 0 ] || sizes=(10000 50000)
[ "$dim" = 2 ] || [ "$dim" = 3 ] || { echo "--dim must be 2 or 3"; exit 2; }
[ -x "$slender" ] || { echo "build slender first (scripts/build.sh)"; exit 2; }
[ -f "$peers/in.wire${dim}d.lmp" ] || { echo "peer decks not found in $peers"; exit 2; }
if [ "$peer" = 1 ] && ! command -v lmp >/dev/null; then
  if [ "$(id -u)" -eq 0 ]; then apt-get install -y -qq lammps >/dev/null; else echo "install lammps (or --no-peer)"; exit 2; fi
fi
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/data"
printf '%-12s %7s %7s %7s %10s %14s\n' code N R steps loop_s node-steps/s
for N in "${sizes[@]}"; do
  # the peer's sizes and run lengths (../shared/peers/run_bench.sh)
  if [ "$dim" = 2 ]; then
    R=100; nrun=5000; nwarm=500; shape=(--shape spiral)
    if [ "$N" -ge 50000 ]; then R=224; nrun=1000; nwarm=200; fi
  else
    R=40; nrun=3000; nwarm=500; shape=()  # 3D: R = 40 at every N (run_bench.sh)
    if [ "$N" -ge 50000 ]; then nrun=1000; nwarm=200; fi
  fi
  data="$work/data/w${dim}d_N$N.data"
  /usr/bin/python3 "$peers/gen_chain.py" --n "$N" --R "$R" --dim "$dim" "${shape[@]}" -o "$data" >/dev/null
  lr=""
  if [ "$peer" = 1 ]; then
    # LAMMPS: the loop time of the second (timed) run
    (cd "$work" && lmp -in "$peers/in.wire${dim}d.lmp" -var N "$N" -var R "$R" -var dt 0.02 \
       -var nwarm "$nwarm" -var nrun "$nrun" -var data "$data" -log "lmp_$N.log" -screen none)
    lt=$(grep "^Loop time" "$work/lmp_$N.log" | sed -n 2p | awk '{print $4}')
    lr=$(awk -v n="$N" -v s="$nrun" -v t="$lt" 'BEGIN{printf "%.4g", n*s/t}')
    printf '%-12s %7s %7s %7s %10s %14s\n' LAMMPS "$N" "$R" "$nrun" "$lt" "$lr"
  fi
  one=""
  for t in $threads; do
    out=$(cd "$work" && "$slender" -t "$t" -q "$root/scripts/bench_wire.lua" -v dim="$dim" -v data="$data" \
            -v R="$R" -v nwarm="$nwarm" -v nrun="$nrun" | grep '^RESULT')
    st=$(echo "$out" | tr ' ' '\n' | sed -n 's/^loop_s=//p')
    sr=$(echo "$out" | tr ' ' '\n' | sed -n 's/^node_steps_per_s=//p')
    printf '%-12s %7s %7s %7s %10.4g %14.4g\n' "slender -t $t" "$N" "$R" "$nrun" "$st" "$sr"
    [ -n "$one" ] || one="$sr"
    [ -z "$lr" ] || awk -v a="$sr" -v b="$lr" -v n="$N" -v t="$t" \
      'BEGIN{printf "ratio slender -t %s / LAMMPS at N = %s: %.2f\n", t, n, a/b}'
    [ "$t" = "$(echo $threads | awk '{print $1}')" ] || awk -v a="$sr" -v b="$one" -v n="$N" -v t="$t" \
      'BEGIN{printf "speed-up of -t %s over the first thread count at N = %s: %.2f\n", t, n, a/b}'
  done
done
