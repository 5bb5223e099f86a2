#!/usr/bin/env bash
# The soak (issue 7): renders FRAMES frames (default 10000) of the default scene headless
# at 320x180, changing the SSS material every 100 frames through the viewer's material
# panel code (10 steps: 9 presets, then a coefficient edit), reads resident memory after
# every frame and records live Vulkan objects every 100 frames. Fails (exit 1) if resident
# memory grows significantly by 1 MB or more over the cycles after warm-up (the first
# cycle, 1000 frames; the statistics are in app/sss-viewer/Soak.h, SoakVerdict: memory is
# judged from 7000 frames on, 6 cycles after warm-up), or if the live Vulkan objects differ
# at the same point of two cycles.
#   scripts/soak.sh [FRAMES]        writes out/soak/soak.csv, soak.svg, soak.log
# 10000 frames took 355 s on lavapipe (35 ms per frame on 2 shared cores). Settings:
#   SSS_SOAK_SCENE (builtin:bunny), SSS_SOAK_SIZE (320x180), SSS_OUT (out),
#   SSS_BUILD_DIR (build); further arguments after FRAMES go to sss-viewer.
set -euo pipefail
cd "$(dirname "$0")/.."
FRAMES="${1:-10000}"
shift || true
case "$FRAMES" in
  '' | *[!0-9]*) echo "soak.sh: error: FRAMES must be a whole number, got '$FRAMES'" >&2; exit 2 ;;
esac
BUILD_DIR="${SSS_BUILD_DIR:-build}"
if [ ! -f "$BUILD_DIR/build.ninja" ]; then
  scripts/install-deps.sh
  cmake -S . -B "$BUILD_DIR" -G Ninja -DCMAKE_BUILD_TYPE="${SSS_BUILD_TYPE:-RelWithDebInfo}" >/dev/null
fi
cmake --build "$BUILD_DIR" --target sss-viewer >/dev/null
SIZE="${SSS_SOAK_SIZE:-320x180}"
OUT="${SSS_OUT:-out}/soak"
mkdir -p "$OUT"
set +e
"$BUILD_DIR/app/sss-viewer/sss-viewer" "${SSS_SOAK_SCENE:-builtin:bunny}" --headless \
  --width "${SIZE%x*}" --height "${SIZE#*x}" --soak "$FRAMES" --soak-every 100 --soak-cycle 10 \
  --soak-csv "$OUT/soak.csv" --soak-svg "$OUT/soak.svg" "$@" 2>&1 | tee "$OUT/soak.log"
rc=${PIPESTATUS[0]}
set -e
exit "$rc"
