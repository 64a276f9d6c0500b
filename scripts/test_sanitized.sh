#!/usr/bin/env bash
# The sanitized subset of the test suite that CI runs (docs/stability.md, "Sanitizers"): an
# AddressSanitizer + UndefinedBehaviorSanitizer build (preset "asan") of the program and of
# the fuzz-corpus replays, running the deck tests of bad input, restarts and a few scenes in
# fast mode, the checkpoint tests (damaged files, kills) and the corpus replays.
# Any finding stops the test that met it (halt_on_error, abort_on_error). The unit tests are
# left out here for time (about 10 more minutes on two cores); run everything with
#   cmake --preset asan && cmake --build --preset asan -j 2 && ctest --preset asan
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc)
cmake --preset asan >/dev/null
cmake --build --preset asan -j"$jobs" --target slender fuzz_deck_table_replay fuzz_mesh_replay \
  fuzz_checkpoint_replay
cd build-asan
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# the decks that check input and restarts (fast under the sanitizers), not the long physics
# decks (a Michell ring or a Cosserat cantilever takes 8-10 min under ASan)
tests='^(deck\.(bad_|unused_variable|deck_features|restart_|main_job_outputs|tutorial_|crumple2d_classic_fast|'
tests+='crumple2d_guard_stop_reports|pack3d_high_torsion_restart|shell_growth_function|shell_plate_clamped|'
# statics: Newton with the exact Hessians, continuation, the shell's edge rules and line load
tests+='cantilever_large_load_newton|continuation_|shell_strip_shear)'
tests+='|checkpoint\.(corrupt_files|kill_safety)|fuzz\.)'
ctest --output-on-failure -j"$jobs" --timeout 1800 -R "$tests"
