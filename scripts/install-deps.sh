#!/usr/bin/env bash
# Installs the Debian 12 packages the build needs. Idempotent: does nothing when they
# are all present. Run as root (or with sudo available).
# --fuzz adds clang 14, its runtime libraries (libFuzzer, ASan, UBSan) and zlib (for the
# instrumented tinyexr, fuzz/ThirdPartyExr.cpp) for the `fuzz`
# preset (scripts/fuzz.sh); the ordinary build and the asan preset use gcc only.
set -euo pipefail

PACKAGES=(
  build-essential cmake ninja-build pkg-config
  libeigen3-dev libcli11-dev nlohmann-json3-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libvulkan-dev glslang-tools mesa-vulkan-drivers vulkan-validationlayers
  libglm-dev libtinygltf-dev libstb-dev libtinyexr-dev
  # Compressed glTF geometry: EXT_meshopt_compression and KHR_draco_mesh_compression.
  libmeshoptimizer-dev libdraco-dev
  libembree-dev libtbb-dev
  assimp-testmodels
  libglfw3-dev libimgui-dev xvfb xauth
  # GNU parallel: the scale-out test runs the README's tile recipe with it
  # (tests/apps/test_sss_reference_random_walk.cpp, GnuParallelSpreadsTilesThatMergeBitIdentically).
  parallel
  # Python 3: the tests compile the Unreal editor script that `sss-fit export --format
  # unreal` writes (tests/profiles/test_engine_profiles.cpp), so a syntax error cannot ship.
  python3-minimal
  # gltfpack (meshoptimizer's): the tests load and render the quantized, texture-transformed
  # files it writes (tests/scene/test_quantized_gltf.cpp, tests/renderer/GltfpackRenderTest.cpp).
  gltfpack
)
if [ "${1:-}" = "--fuzz" ]; then
  PACKAGES+=(clang-14 libclang-rt-14-dev zlib1g-dev)
fi

# The JavaScript tools the tests run, pinned in tools/node's package-lock.json: the
# Khronos glTF-Validator (npm gltf-validator), run over every glTF the project writes, and
# glTF-Transform's libraries with npm's Draco and meshoptimizer encoders, which write the
# compressed and KHR-extension files the loader is tested on (tools/node/variants.mjs;
# the libraries, not @gltf-transform/cli, whose 4.x needs node >= 20 and Debian 12 has
# 18). Node and npm from Debian (nodejs, npm) unless a node with npm is there already.
VALIDATOR_DIR="$(cd "$(dirname "$0")/../tools/node" && pwd)"
install_validator() {
  local m="$VALIDATOR_DIR/node_modules"
  [ -f "$m/gltf-validator/package.json" ] && [ -f "$m/@gltf-transform/extensions/package.json" ] &&
    [ -f "$m/draco3dgltf/package.json" ] && [ -f "$m/meshoptimizer/package.json" ] && return 0
  (cd "$VALIDATOR_DIR" && npm ci --no-audit --no-fund --loglevel=error)
}
if ! command -v npm >/dev/null 2>&1; then
  command -v node >/dev/null 2>&1 || PACKAGES+=(nodejs)
  PACKAGES+=(npm)
fi

missing=()
for p in "${PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  install_validator
  exit 0
fi

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "Installing: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
install_validator
