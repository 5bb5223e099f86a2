#!/usr/bin/env bash
# Runs every test that creates a Vulkan context (ctest labels vk and renderer: the
# renderer/vk fixture, the renderer tests and the sss-viewer processes they launch) once
# per validation mode, each run separately and each of which must be clean:
#   core            the layer's default checks
#   sync            core + synchronization validation (what scripts/test.sh runs too)
#   best-practices  core + best practices (a few IDs dropped with their reasons:
#                   kIgnoredMessages in renderer/vk/ValidationLog.cpp)
# The mode reaches every Context through SSS_VALIDATION_CHECKS (renderer/vk/Environment.h);
# a Context asked for a mode without the layer installed throws, so a run cannot pass
# without checking. Any message of the layer fails the test that caused it.
#
# Usage: scripts/test-validation.sh [MODE...] [-- CTEST_ARGS...]
#   default modes: core sync best-practices; CTEST_ARGS default: -L '^(vk|renderer)$'
#   e.g. scripts/test-validation.sh best-practices -- -L vk
# SSS_BUILD_DIR (default build) is configured and built first as scripts/test.sh does
# (a no-op when it is up to date).
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR="${SSS_BUILD_DIR:-build}"

modes=()
while [ $# -gt 0 ] && [ "$1" != "--" ]; do
  case "$1" in
    core|sync|best-practices) modes+=("$1") ;;
    *) echo "test-validation.sh: unknown mode '$1' (core, sync, best-practices)" >&2; exit 2 ;;
  esac
  shift
done
[ $# -gt 0 ] && shift  # the --
[ ${#modes[@]} -gt 0 ] || modes=(core sync best-practices)
ctest_args=("$@")
[ ${#ctest_args[@]} -gt 0 ] || ctest_args=(-L '^(vk|renderer)$')

SSS_BUILD_DIR="$BUILD_DIR" scripts/build.sh -DSSS_WERROR=ON

# The layer must be there (Debian: vulkan-validationlayers, installed by install-deps.sh).
if ! ls /usr/share/vulkan/explicit_layer.d/VkLayer_khronos_validation.json >/dev/null 2>&1; then
  echo "test-validation.sh: VK_LAYER_KHRONOS_validation is not installed" \
       "(Debian: vulkan-validationlayers)" >&2
  exit 1
fi

status=0
for mode in "${modes[@]}"; do
  start=$(date +%s)
  if SSS_VALIDATION_CHECKS="$mode" ctest --test-dir "$BUILD_DIR" --output-on-failure \
       -j"$(nproc)" --timeout 900 "${ctest_args[@]}"; then
    result=passed
  else
    result=FAILED
    status=1
  fi
  echo "validation mode $mode: $result in $(( $(date +%s) - start )) s"
done
exit $status
