#!/usr/bin/env bash
# The README's main command. With a display (DISPLAY or WAYLAND_DISPLAY set) it opens the
# interactive viewer on the default scene (builtin:bunny, the Stanford bunny in skin1,
# screen-space SSS). Without one it renders that scene headlessly to out/bunny.png and
# out/bunny.exr with per-pass timings (lavapipe when there is no GPU), then fits skin1's
# profile with 6 Gaussians (out/skin1-fit.svg, kernel JSON and C header). Extra arguments
# go to sss-viewer, e.g.
#   scripts/run.sh --mode gaussians --width 1280 --height 720
# SSS_HEADLESS=1 renders to files even when a display is present.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh >/dev/null
if [ -z "${SSS_HEADLESS:-}" ] && { [ -n "${DISPLAY:-}" ] || [ -n "${WAYLAND_DISPLAY:-}" ]; }; then
  exec build/app/sss-viewer/sss-viewer builtin:bunny "$@"
fi
OUT="${SSS_OUT:-out}"
mkdir -p "$OUT"
build/app/sss-viewer/sss-viewer builtin:bunny --headless --out "$OUT/bunny.png" --stats "$@"
build/app/sss-viewer/sss-viewer builtin:bunny --headless --out "$OUT/bunny.exr" "$@" >/dev/null
echo "wrote $OUT/bunny.png (tonemapped) and $OUT/bunny.exr (linear radiance)"
echo
build/app/sss-fit/sss-fit fit --preset skin1 --gaussians 6 --taps 17 \
  --out "$OUT/skin1-kernel.json" --plot "$OUT/skin1-fit.svg" --plot-mc --photons 200000
build/app/sss-fit/sss-fit fit --preset skin1 --gaussians 6 --taps 17 \
  --out "$OUT/skin1-kernel.h" --json >/dev/null
echo "Open $OUT/bunny.png, and $OUT/skin1-fit.svg for r*R(r) of the model, the fit and Monte Carlo."
