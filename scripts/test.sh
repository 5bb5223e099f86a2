#!/usr/bin/env bash
# The README's test command: installs what it needs, builds everything with warnings as
# errors, and runs every test. Exit code non-zero on any failure.
set -euo pipefail
cd "$(dirname "$0")/.."
SSS_BUILD_DIR="${SSS_BUILD_DIR:-build}" scripts/build.sh -DSSS_WERROR=ON
ctest --test-dir "${SSS_BUILD_DIR:-build}" --output-on-failure -j"$(nproc)" --timeout 600
