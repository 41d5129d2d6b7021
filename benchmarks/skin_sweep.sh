#!/usr/bin/env bash
# Throughput of a scene against the neighbour-list skin (see setting_sweep.sh). A larger skin
# means fewer list builds but longer lists: where the optimum lies depends on how fast
# particles move (hot walls, turning beds).
# usage: benchmarks/skin_sweep.sh RANKS SETTLE TIMED REPEATS "SKINS" SCENE [--set key=value]...
set -euo pipefail
ranks=$1 settle=$2 timed_steps=$3 repeats=$4 skins=$5
shift 5
exec "$(dirname "$0")/setting_sweep.sh" "$ranks" "$settle" "$timed_steps" "$repeats" skin "$skins" "$@"
