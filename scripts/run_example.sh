#!/usr/bin/env bash
# Sets up, builds and runs the main job: the cantilever validation deck with
# thermo (CSV) and trajectory (H5MD + XDMF) output in out/.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
mkdir -p out
cd out
../build/slender ../examples/validation/cantilever2d.lua -v output=true -v alpha=3 "$@"
echo "outputs: out/cantilever2d_thermo.csv, out/cantilever2d.h5 (+ .xdmf for ParaView)"
