#!/usr/bin/env bash
# Builds in Release and runs the benchmarks. Arguments go to Google Benchmark, e.g.
#   scripts/bench.sh --benchmark_filter=Fit
# (each program runs the filter over its own benchmarks: bench_profiles, bench_reference,
# bench_random_walk, bench_refit, bench_gltf_load)
set -euo pipefail
cd "$(dirname "$0")/.."
SSS_BUILD_DIR=build-release SSS_BUILD_TYPE=Release scripts/build.sh >/dev/null
build-release/bench/bench_profiles "$@"
if [ -x build-release/bench/bench_reference ]; then build-release/bench/bench_reference "$@"; fi
if [ -x build-release/bench/bench_random_walk ]; then build-release/bench/bench_random_walk "$@"; fi
if [ -x build-release/bench/bench_refit ]; then build-release/bench/bench_refit "$@"; fi
if [ -x build-release/bench/bench_gltf_load ]; then build-release/bench/bench_gltf_load "$@"; fi
