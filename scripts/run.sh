#!/usr/bin/env bash
# The README's main command. Until the viewer lands (issue 5) the main job is sss-fit on
# the default material: fit skin1 (Jensen 2001) with 6 Gaussians, print the fit, write
# the kernel (JSON and C header) and a plot of the profile against the fit and Monte Carlo.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build.sh >/dev/null
OUT="${SSS_OUT:-out}"
mkdir -p "$OUT"
build/app/sss-fit/sss-fit fit --preset skin1 --model better-dipole --gaussians 6 --taps 17 \
  --out "$OUT/skin1-kernel.json" --plot "$OUT/skin1-fit.svg" --plot-mc --photons 200000 "$@"
build/app/sss-fit/sss-fit fit --preset skin1 --model better-dipole --gaussians 6 --taps 17 \
  --out "$OUT/skin1-kernel.h" --json >/dev/null
echo "Open $OUT/skin1-fit.svg to see r*R(r) of the model, the fit and Monte Carlo."
