#!/usr/bin/env bash
# The 2D peer comparison (kept for its name): scripts/bench_peer.sh --dim 2 [N ...]
exec "$(dirname "$0")/bench_peer.sh" --dim 2 "$@"
