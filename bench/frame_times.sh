#!/usr/bin/env bash
# Frame-time benchmark of the real-time renderer (issue 3): builtin:bunny rendered
# headlessly at 640x360 and 1280x720 with SSS off, separable and gaussians, N frames each,
# per-pass GPU times from `sss-viewer --stats`. Ratios are taken within this run: each
# configuration against `off` at the same size, and the SSS pass's share of its frame.
#   bench/frame_times.sh [FRAMES] [VIEWER]      (default 5 frames, build-release viewer)
# On lavapipe the "GPU" times are CPU times of the Vulkan driver; use --device to pick
# a real GPU where one exists.
set -euo pipefail
cd "$(dirname "$0")/.."
FRAMES="${1:-5}"
VIEWER="${2:-build-release/app/sss-viewer/sss-viewer}"
if [ ! -x "$VIEWER" ]; then
  SSS_BUILD_DIR=build-release SSS_BUILD_TYPE=Release scripts/build.sh >/dev/null
fi
OUT="$(mktemp -d)"
trap 'rm -rf "$OUT"' EXIT

# Mean GPU total and SSS pass time (ms) over the frames, from --stats.
measure() {
  "$VIEWER" builtin:bunny --headless --out "$OUT/f.png" --frames "$FRAMES" --stats "$@" |
    awk '/^gpu total/ {t=$3} /^sss / {s=$(NF)} END {printf "%s %s\n", t, (s==""?0:s)}'
}

printf "%-10s %-10s %12s %12s %10s %10s\n" size mode "frame ms" "sss ms" "sss share" "vs off"
for size in 640x360 1280x720; do
  w=${size%x*}; h=${size#*x}
  read -r off_total _ < <(measure --width "$w" --height "$h" --sss off)
  printf "%-10s %-10s %12.1f %12s %10s %10s\n" "$size" off "$off_total" - - 1.00
  for mode in separable gaussians; do
    read -r total sss < <(measure --width "$w" --height "$h" --sss screen --mode "$mode")
    awk -v s="$size" -v m="$mode" -v t="$total" -v p="$sss" -v o="$off_total" \
      'BEGIN {printf "%-10s %-10s %12.1f %12.1f %9.0f%% %9.2fx\n", s, m, t, p, 100*p/t, t/o}'
  done
done
