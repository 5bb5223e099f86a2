#!/usr/bin/env bash
# Per-pass GPU times of issue 5's frame-rate target: builtin:bunny, 960x540, screen
# separable SSS (>= 15 fps on 2 CPU cores with lavapipe). Runs bench_frame (bench/frame:
# min and median per pass over FRAMES frames after warm-up, and the process's CPU time
# per frame) RUNS times, alternating with an optional second build for a same-run
# comparison (on a shared machine, compare minima taken in the same run only).
#   bench/pass_times.sh [BUILD_DIR] [BASELINE_BENCH_FRAME] [-- bench_frame options]
#   e.g. bench/pass_times.sh build-live /tmp/bench_frame.before -- --width 1920 --height 1080
# LP_NUM_THREADS=1 measures one lavapipe worker (the least noisy figure on a busy machine).
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD="build-live"
BASE=""
if [ $# -gt 0 ] && [ "$1" != "--" ]; then BUILD="$1"; shift; fi
if [ $# -gt 0 ] && [ "$1" != "--" ]; then BASE="$1"; shift; fi
[ $# -gt 0 ] && [ "$1" = "--" ] && shift
RUNS="${RUNS:-3}"
FRAMES="${FRAMES:-10}"
BENCH="$BUILD/bench/bench_frame"
if [ ! -x "$BENCH" ]; then cmake --build "$BUILD" --target bench_frame >/dev/null; fi

for ((i = 1; i <= RUNS; ++i)); do
  for b in ${BASE:+"$BASE"} "$BENCH"; do
    echo "== $b (run $i)"
    "$b" builtin:bunny --width 960 --height 540 --sss screen --mode separable \
      --frames "$FRAMES" "$@"
  done
done
