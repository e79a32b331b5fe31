#!/usr/bin/env bash
# ./setup.sh sanitize: the sanitizer stage of CI (.ci/run runs it after the
# tests). Every part prints its wall and CPU time ("timing: ..."):
#   1. an ASan+UBSan build (clang -O1, LeakSanitizer on, lsan.supp for Mesa's
#      leaks) of everything, the whole test suite on it, and 30 s of each fuzz
#      target over its seed corpus (FUZZ_SECONDS to change);
#   2. oneTBB built with TSan from Debian's source package (once, kept in the
#      build tree), a TSan build of the tests on it, and the threaded tests and
#      the canary (tsan_canary.cpp) under it: zero reports, and the canary's
#      planted race reported.
# Any sanitizer report fails it. See docs/fuzzing-and-sanitizers.md.
set -euo pipefail
source "$(dirname "$0")/common.sh"
tsan_dir=${CROWDPROF_TSAN_DIR:-$root/build-tsan}

echo "sanitize: ASan+UBSan build in $asan_dir" >&2
timed "ASan+UBSan build" build_asan >/dev/null
timed "ASan+UBSan test suite" ctest --test-dir "$asan_dir" -j"$jobs" --output-on-failure >"$asan_dir/ctest.log" 2>&1 ||
  lsan_crash_only "$asan_dir" ||
  { explain_failures "$asan_dir"; echo "sanitize: the test suite failed under ASan+UBSan" >&2; exit 1; }
tail -n 3 "$asan_dir/ctest.log"
# A fixed seed: the same code fuzzes the same inputs, so CI is not red by luck
# and a finding here is reproduced by running the stage again.
FUZZ_SEED=${FUZZ_SEED:-1} timed "fuzzing, ${FUZZ_SECONDS:-30} s per target" "$root/tests/sanitizers/fuzz.sh" "${FUZZ_SECONDS:-30}"

echo "sanitize: TSan build in $tsan_dir" >&2
mkdir -p "$tsan_dir"
timed "oneTBB with TSan" "$root/tests/sanitizers/onetbb_tsan.sh" "$tsan_dir"
build_tsan() {
  CC=clang CXX=clang++ cmake -S "$root" -B "$tsan_dir/crowdprof" -G Ninja -DCMAKE_BUILD_TYPE=Sanitize \
    -DCMAKE_CXX_FLAGS_SANITIZE="-O1 -gline-tables-only" -DCMAKE_C_FLAGS_SANITIZE="-O1 -gline-tables-only" \
    -DCROWDPROF_SANITIZE=thread -DTBB_DIR="$tsan_dir/onetbb-install/lib/cmake/TBB" >/dev/null
  cmake --build "$tsan_dir/crowdprof" -j"$jobs" --target crowdprof_threaded_tests crowdprof_cli tsan_canary
}
timed "TSan build" build_tsan >/dev/null
# The tests that run threads (the threaded mode, compare's and check's runs,
# traces of workers) and the canary; TSan exits 66 on any report.
threaded='^threaded\.|^tsan_canary\.'
export TSAN_OPTIONS=second_deadlock_stack=1:suppressions=$root/tests/sanitizers/tsan.supp
timed "TSan threaded tests" ctest --test-dir "$tsan_dir/crowdprof" -R "$threaded" -j"$jobs" --output-on-failure \
  >"$tsan_dir/ctest.log" 2>&1 ||
  { explain_failures "$tsan_dir" "$tsan_dir/crowdprof"; echo "sanitize: the threaded tests failed under TSan" >&2; exit 1; }
tail -n 3 "$tsan_dir/ctest.log"
echo "sanitize: no sanitizer reports" >&2
