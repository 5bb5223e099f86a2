#!/bin/sh
# One bless script for both halves of the golden-frame suite:
#   regression/  the GPU frames of GoldenTest.cpp against themselves (exact tolerances):
#                re-renders regression/NAME.png;
#   reference/   every real-time mode against the CPU reference (ReferenceSuiteTest.cpp):
#                refreshes each case's blur_link (the GPU frame against the reference
#                with the fit and the shadow maps, from which the limit is derived in
#                every run) and the measured total in reference/tolerances.json (the
#                reasons are kept; a new case must get its reason written by hand) and
#                rewrites tests/golden/REPORT.md.
# Images of every case (GPU, reference, heat map) land in BUILD_DIR/tests/golden-out/.
# Usage: tests/golden/bless.sh [BUILD_DIR]   (default: build). Look at every changed PNG and
# at the report's diff (git diff tests/golden) before committing.
set -eu
build="${1:-build}"
cd "$build/tests"
SSS_BLESS=1 ./test_renderer --gtest_filter='*GoldenTest*:*ReferenceSuiteTest*'
cd - >/dev/null
git -C "$(dirname "$0")/../.." status --short tests/golden
