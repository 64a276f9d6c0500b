#!/usr/bin/env bash
# Speed against the peer: the 2D wire in a circular cavity, slender vs LAMMPS, at the
# same N, start configuration (../shared/peers/gen_chain.py spiral), dt and steps,
# run one after the other on this machine. Prints node-steps/s of each and the ratio.
# A benchmark, not a test. Needs LAMMPS (Debian package lammps; installed if missing
# and we are root).   scripts/bench_peer_wire2d.sh [N ...]   (default: 10000 50000)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
peers="${PEERS:-$root/../shared/peers}"
slender="${SLENDER:-$root/build/slender}"
[ -x "$slender" ] || { echo "build slender first (scripts/build.sh)"; exit 2; }
[ -f "$peers/in.wire2d.lmp" ] || { echo "peer decks not found in $peers"; exit 2; }
if ! command -v lmp >/dev/null; then
  if [ "$(id -u)" -eq 0 ]; then apt-get install -y -qq lammps >/dev/null; else echo "install lammps"; exit 2; fi
fi
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/data"
sizes=("${@:-10000 50000}")
[ $# -gt 0 ] || sizes=(10000 50000)
printf '%-8s %7s %7s %7s %10s %14s\n' code N R steps loop_s node-steps/s
for N in "${sizes[@]}"; do
  R=100; nrun=5000; nwarm=500
  if [ "$N" -ge 50000 ]; then R=224; nrun=1000; nwarm=200; fi
  data="$work/data/w2d_N$N.data"
  /usr/bin/python3 "$peers/gen_chain.py" --n "$N" --R "$R" --dim 2 --shape spiral -o "$data" >/dev/null
  # LAMMPS: the loop time of the second (timed) run
  (cd "$work" && lmp -in "$peers/in.wire2d.lmp" -var N "$N" -var R "$R" -var dt 0.02 \
     -var nwarm "$nwarm" -var nrun "$nrun" -log "lmp_$N.log" -screen none)
  lt=$(grep "^Loop time" "$work/lmp_$N.log" | sed -n 2p | awk '{print $4}')
  lr=$(awk -v n="$N" -v s="$nrun" -v t="$lt" 'BEGIN{printf "%.4g", n*s/t}')
  printf '%-8s %7s %7s %7s %10s %14s\n' LAMMPS "$N" "$R" "$nrun" "$lt" "$lr"
  # slender on the same start
  out=$(cd "$work" && "$slender" -q "$root/scripts/bench_wire2d.lua" -v data="$data" -v R="$R" \
          -v nwarm="$nwarm" -v nrun="$nrun" | grep '^RESULT')
  st=$(echo "$out" | tr ' ' '\n' | sed -n 's/^loop_s=//p')
  sr=$(echo "$out" | tr ' ' '\n' | sed -n 's/^node_steps_per_s=//p')
  printf '%-8s %7s %7s %7s %10.4g %14.4g\n' slender "$N" "$R" "$nrun" "$st" "$sr"
  awk -v a="$sr" -v b="$lr" -v n="$N" 'BEGIN{printf "ratio slender / LAMMPS at N = %s: %.2f\n", n, a/b}'
done
