#!/bin/sh
# Re-renders the golden frames of tests/renderer/GoldenTest.cpp into tests/renderer/golden/.
# Usage: tests/renderer/bless.sh [BUILD_DIR]   (default: build). Look at every changed PNG
# (git diff --stat, an image viewer) before committing it.
set -eu
build="${1:-build}"
SSS_BLESS=1 "$build/tests/test_renderer" --gtest_filter='*GoldenTest*'
git -C "$(dirname "$0")/../.." status --short tests/renderer/golden
