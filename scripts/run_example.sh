#!/usr/bin/env bash
# The main job: sets up (scripts/setup.sh), builds (scripts/build.sh) and runs a small
# crumpling scene: the classic deck (examples/crumple2d/classic.lua) in a cavity of
# f = 30 wire diameters until the wire jams, 30-40 s on one core; the deck draws the last
# frame as a PNG (python3 -m slender render), and this script says how to open the
# trajectory in ParaView. Everything goes to out/.
#
#   bash scripts/run_example.sh [-v name=value ...]             the crumpling run
#                                                              (-v f=50: ~5 min, ...)
#   bash scripts/run_example.sh cantilever [-v name=value ...]  the validation case: a
#                                      clamped wire under a large tip load against the
#                                      elastica (out/cantilever2d_thermo.csv, .h5, .xdmf)
set -euo pipefail
cd "$(dirname "$0")/.."
root="$PWD"
mode=crumple
if [[ "${1:-}" == cantilever ]]; then mode=cantilever; shift; fi
if [[ "${1:-}" == -h || "${1:-}" == --help ]]; then sed -n '2,12p' "$0" | sed 's/^# \{0,1\}//'; exit 0; fi

bash scripts/setup.sh
mkdir -p out
echo "build: compiling slender in build/ (minutes the first time; log in out/build.log)"
if ! bash scripts/build.sh > out/build.log 2>&1; then
  tail -n 30 out/build.log
  echo "build: failed, see out/build.log" >&2
  exit 1
fi
echo "build: build/slender is up to date"
cd out

if [[ $mode == cantilever ]]; then
  ../build/slender ../examples/validation/cantilever2d.lua -v output=true -v alpha=3 "$@"
  echo "outputs: out/cantilever2d_thermo.csv, out/cantilever2d.h5 (+ .xdmf for ParaView)"
  exit 0
fi

# the cavity radius f (in wire diameters) is also the render's circle: take it out of the
# -v overrides
f=30 args=()
while [[ $# -gt 0 ]]; do
  if [[ $1 == -v && ${2:-} == f=* ]]; then f="${2#f=}"; shift 2; else args+=("$1"); shift; fi
done
rm -f classic.h5 classic.h5.xdmf classic_thermo.csv classic.png classic.log
echo "run: examples/crumple2d/classic.lua -v f=$f${args[*]:+ ${args[*]}}"
echo "     a wire pushed from two channels into a circular cavity of radius $f wire"
echo "     diameters until it jams ($([[ $f == 30 ]] && echo "30-40 s, ")console in out/classic.log)"
start=$(date +%s.%N)
../build/slender ../examples/crumple2d/classic.lua -v f="$f" ${args[@]+"${args[@]}"} > classic.log 2>&1 || {
  tail -n 20 classic.log
  echo "run: slender stopped with an error, the whole console is in out/classic.log" >&2
  exit 1
}
wall=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.1f", b - a }')
# the deck's summary is its RESULT line (key=value pairs)
grep '^RESULT ' classic.log | tail -n 1 | tr ' ' '\n' | awk -F= -v wall="$wall" '
  NF == 2 { r[$1] = $2 }
  END {
    printf "run: %s after %d steps and %s s: packing density phi = %.3f, %d nodes, %d contacts, %d loops\n",
      (r["jammed"] == 1 ? "jammed" : "stopped"), r["steps"], wall, r["phi"], r["nodes"], r["contacts"], r["loops"]
  }'
# the deck draws its last frame (examples/lib/snapshot.lua); without Python's matplotlib
# and h5py it says so in its console
grep -q '^picture: classic.png' classic.log || echo "run: no picture (see out/classic.log)" >&2
cat <<EOF

  picture     out/classic.png          (the last frame, coloured by plastic curvature)
  trajectory  out/classic.h5           (H5MD; PYTHONPATH=python python3 -m slender info out/classic.h5)
  thermo      out/classic_thermo.csv   (phi, force, contacts, loops, energies per row)
  console     out/classic.log

Open the trajectory in ParaView (press Play to watch the wire fold):

  paraview out/classic.h5.xdmf

(when ParaView asks for a reader, choose "XDMF Reader": it draws each wire as one polyline). Next: a bigger cavity with
'bash scripts/run_example.sh -v f=50' (about 5 minutes), the other scenes in examples/README.md.
EOF
