#!/usr/bin/env bash
# Issue 6's texture-space benchmarks on lavapipe (bench/frame/bench_frame, per-pass minimum
# and median over FRAMES frames after one warm-up frame; compare minima, taken in this run):
#   1. cost of the texture path against the irradiance texture size, 256^2 .. 2048^2
#      (builtin:bunny, 960x540, every-frame updates so the atlas work runs each frame);
#   2. the texture path against the screen path at 1280x720, for one and for three SSS
#      objects (--objects 3: three bunnies), with every-frame and on-change updates (the
#      latter: a still scene or a moving camera costs only the lookup).
#   bench/texture_space.sh [BUILD_DIR]      FRAMES=5 by default
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD="${1:-build}"
FRAMES="${FRAMES:-5}"
BENCH="$BUILD/bench/bench_frame"
if [ ! -x "$BENCH" ]; then cmake --build "$BUILD" --target bench_frame >/dev/null; fi
run() { "$BENCH" builtin:bunny --frames "$FRAMES" --warmup 1 "$@"; }

echo "### 1. texture path cost against the irradiance texture size (960x540, every frame)"
for size in 256 512 1024 2048; do
  run --width 960 --height 540 --sss texture --texture-size "$size" --texture-update every-frame
done
echo "### 2. texture against screen at 1280x720, 1 and 3 objects"
for objects in 1 3; do
  run --width 1280 --height 720 --objects "$objects" --sss screen --mode separable
  run --width 1280 --height 720 --objects "$objects" --sss screen --mode gaussians
  run --width 1280 --height 720 --objects "$objects" --sss texture --texture-size 1024 --texture-update every-frame
  run --width 1280 --height 720 --objects "$objects" --sss texture --texture-size 1024 --texture-update on-change
done
