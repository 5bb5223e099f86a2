#!/bin/sh
# One bless script for both halves of the golden-frame suite:
#   regression/  the GPU frames of GoldenTest.cpp against themselves (exact tolerances):
#                re-renders regression/NAME.png;
#   reference/   every real-time mode against the CPU reference (ReferenceSuiteTest.cpp):
#                refreshes the measured values in reference/tolerances.json (limits and
#                reasons are kept; a new case gets measured x 1.25 and must get its reason
#                written by hand) and rewrites tests/golden/REPORT.md.
# Images of every case (GPU, reference, heat map) land in BUILD_DIR/tests/golden-out/.
# Usage: tests/golden/bless.sh [BUILD_DIR]   (default: build). Look at every changed PNG and
# at the report's diff (git diff tests/golden) before committing.
set -eu
build="${1:-build}"
cd "$build/tests"
SSS_BLESS=1 ./test_renderer --gtest_filter='*GoldenTest*:*ReferenceSuiteTest*'
cd - >/dev/null
git -C "$(dirname "$0")/../.." status --short tests/golden
