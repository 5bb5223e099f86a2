#!/bin/sh
# Renders the stored ground truths (issue 16): sss-reference --method random-walk for the
# golden suite's scenes at the suite's sizes, each to 1% relative standard error or better,
# with its variance (the variance of each pixel's mean), a PNG to look at, and a JSON
# summary holding the exact command, the samples per pixel, the error reached, the time,
# the machine and the commit. ReferenceSuiteTest (tests/renderer) reads them and never
# renders them; the Z-test of test_ground_truth_render (tests/reference) reads zsphere.
#
# Usage: tests/golden/ground-truth/render.sh [BUILD_DIR] [NAME...]   (default: build, all)
# The renders are deterministic for their seed (bit for bit, whatever the thread count),
# so a re-render reproduces the files unless the walk changed. Spread over machines with
# --tile (README, "Scale-out").
set -eu
build="${1:-build}"
[ $# -gt 0 ] && shift
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../../.." && pwd)"
exe="$(cd "$build" 2>/dev/null && pwd)/app/sss-reference/sss-reference"
dir=tests/golden/ground-truth  # from the repository root: the summaries name these paths
[ -x "$exe" ] || { echo "render.sh: $exe not built (scripts/build.sh)" >&2; exit 2; }
only="$*"

render() {
  name="$1"
  shift
  case " $only " in *" $name "*|"  ") ;; *) return 0 ;; esac
  echo "render.sh: $name" >&2
  "$exe" "$@" --method random-walk --out "$dir/$name.exr" --variance "$dir/$name.var.exr" \
    --png "$dir/$name.png" --summary "$dir/$name.tmp.json"
  # The summary, with where and from what it was made.
  commit=$(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo unknown)
  dirty=$(git -C "$root" status --porcelain -- renderer profiles app 2>/dev/null | head -c1)
  cpu=$(sed -n 's/^model name[[:space:]]*: //p' /proc/cpuinfo | head -n1)
  {
    echo "{"
    echo "  \"made_by\": \"tests/golden/ground-truth/render.sh\","
    echo "  \"date\": \"$(date -u +%Y-%m-%dT%H:%M:%SZ)\","
    echo "  \"commit\": \"$commit${dirty:+ (with uncommitted changes)}\","
    echo "  \"machine\": \"$(nproc) cores, $cpu\","
    sed '1d' "$dir/$name.tmp.json"
  } > "$dir/$name.json"
  rm -f "$dir/$name.tmp.json"
}

cd "$root"
# The suite's scenes (tests/renderer/ReferenceSuiteTest.cpp), each scene's own materials.
render edge builtin:edge --width 128 --height 16 --target-error 0.01
render sphere builtin:sphere --width 160 --height 90 --target-error 0.01
render bunny builtin:bunny --width 160 --height 90 --target-error 0.01
render slab builtin:slab --width 160 --height 90 --target-error 0.01
render materials builtin:materials --width 240 --height 135 --target-error 0.01
render textured_tile assets/textured_tile.glb --width 160 --height 90 --target-error 0.01
# The Z-test's reference: small, and far less noisy than the 256-sample render it judges.
render zsphere builtin:sphere --width 32 --height 18 --spp 16384 --seed 1
