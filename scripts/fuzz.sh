#!/usr/bin/env bash
# Fuzzes every target of fuzz/FuzzTargets.h for SECONDS each (default 30) with libFuzzer,
# ASan and UBSan (the `fuzz` preset, clang 14, in build-fuzz/). Each target starts from
# its committed seeds (fuzz/corpus/<target>/; the glTF loader also from tests/data/bad/)
# and keeps what it finds in build-fuzz/corpus-work/<target>/ (not committed) for the
# next run. Prints per target the executions, exec/s and the final cov/ft figures; exits
# non-zero on any crash, leak, timeout, out-of-memory or sanitizer report, with the
# reproducer's path (build-fuzz/artifacts/<target>/) in the output.
#
# A reproducer becomes a regression: minimize it
#   build-fuzz/fuzz/fuzz_<target> -minimize_crash=1 -runs=10000 REPRODUCER
# and commit it as fuzz/regressions/<target>/<class>.<ext> (or <class>.<ext>.pending
# until the fix lands), so that test_fuzz_replay (scripts/test.sh, scripts/test-asan.sh)
# replays it forever. Usage: scripts/fuzz.sh [SECONDS] [TARGET...]
set -euo pipefail
cd "$(dirname "$0")/.."
"$(dirname "$0")/install-deps.sh" --fuzz

SECONDS_PER_TARGET="${1:-30}"
shift || true
TARGETS=("$@")
if [ ${#TARGETS[@]} -eq 0 ]; then TARGETS=(gltf sss_extras medium_args image); fi
BUILD_DIR=build-fuzz

nice -n 19 cmake --preset fuzz >/dev/null
nice -n 19 cmake --build --preset fuzz -j"$(nproc)"

# Largest input per target: the biggest seed with room to grow (glTF: textured_tile.glb
# is 14 KB), the rest are small texts and images.
declare -A MAX_LEN=([gltf]=65536 [sss_extras]=4096 [medium_args]=1024 [image]=8192)
declare -A EXTRA_SEEDS=([gltf]="tests/data/bad")

# ASan/UBSan halt on the first report; leak detection stays on (libFuzzer checks leaks
# per input). UBSan reports are fatal through -fno-sanitize-recover (CMakePresets.json).
export ASAN_OPTIONS="halt_on_error=1:detect_leaks=1${ASAN_OPTIONS:+:$ASAN_OPTIONS}"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"

failed=()
summary=()
for t in "${TARGETS[@]}"; do
  exe="$BUILD_DIR/fuzz/fuzz_$t"
  [ -x "$exe" ] || { echo "fuzz: no target '$t' ($exe)"; exit 2; }
  work="$BUILD_DIR/corpus-work/$t"
  artifacts="$BUILD_DIR/artifacts/$t"
  log="$BUILD_DIR/fuzz-$t.log"
  mkdir -p "$work" "$artifacts"
  seeds=("fuzz/corpus/$t")
  for s in ${EXTRA_SEEDS[$t]:-}; do seeds+=("$s"); done
  echo "== fuzz_$t: ${SECONDS_PER_TARGET}s, -max_len=${MAX_LEN[$t]}, seeds ${seeds[*]}, log $log"
  rc=0
  nice -n 19 "$exe" -max_total_time="$SECONDS_PER_TARGET" -max_len="${MAX_LEN[$t]}" \
    -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 -artifact_prefix="$artifacts/" \
    "$work" "${seeds[@]}" >"$log" 2>&1 || rc=$?
  # The last status line ("#N DONE cov: C ft: F corp: ...") and the final stats.
  status_line="$(grep -E '^#[0-9]+' "$log" | tail -n 1 || true)"
  runs="$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)"
  speed="$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -n 1)"
  cov="$(sed -n 's/.* cov: \([0-9]*\).*/\1/p' <<<"$status_line")"
  ft="$(sed -n 's/.* ft: \([0-9]*\).*/\1/p' <<<"$status_line")"
  corp="$(sed -n 's/.* corp: \([^ ]*\).*/\1/p' <<<"$status_line")"
  line="$(printf '%-12s runs %-9s exec/s %-7s cov %-6s ft %-6s corpus %s' "$t" "${runs:-?}" "${speed:-?}" "${cov:-?}" "${ft:-?}" "${corp:-?}")"
  if [ "$rc" -ne 0 ]; then
    # libFuzzer names the reproducer: "Test unit written to PATH".
    repro="$(sed -n 's/.*Test unit written to \(.*\)/\1/p' "$log" | tail -n 1)"
    grep -E 'ERROR: |SUMMARY: |runtime error|fuzz invariant broken|deadly signal|out-of-memory|timeout' "$log" | head -n 20 || true
    echo "fuzz_$t FAILED (exit $rc): reproducer ${repro:-none written}; full log $log"
    echo "  replay: $exe ${repro:-REPRODUCER}"
    failed+=("$t")
    line="$line  FAILED: ${repro:-see $log}"
  fi
  echo "$line"
  summary+=("$line")
done

echo "== fuzz summary (${SECONDS_PER_TARGET}s per target)"
printf '%s\n' "${summary[@]}"
if [ ${#failed[@]} -ne 0 ]; then
  echo "fuzz: findings in ${failed[*]}"
  exit 1
fi
echo "fuzz: no findings"
