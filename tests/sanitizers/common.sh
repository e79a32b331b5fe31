# Shared by the sanitizer scripts (sourced): the ASan+UBSan+libFuzzer build,
# the sanitizers' options and a timer that says what each part cost.
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
asan_dir=${CROWDPROF_ASAN_DIR:-$root/build-sanitize}
jobs=$(nproc)

# Reports are failures; LeakSanitizer skips only what lsan.supp names (Mesa's).
# intercept_tls_get_addr=0: LLVM 14's __tls_get_addr interceptor takes a dynamic
# TLS block that happens to start 16 bytes into a page for glibc 2.19's header
# and records two words before it as a range to scan; LeakSanitizer's tracer
# then reads that range at exit and dies ("Tracer caught signal 11"). Mesa's
# llvmpipe (dlopen'd, with dynamic TLS) can make that happen, by chance of where
# its TLS block lands. Without the interceptor no dynamic TLS is scanned; the
# suite reports no leak without it.
export ASAN_OPTIONS=detect_leaks=1:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1:intercept_tls_get_addr=0
export LSAN_OPTIONS=suppressions=$root/tests/sanitizers/lsan.supp:print_suppressions=0
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1

# timed NAME COMMAND...: runs it, then prints on stderr what it cost: wall time
# and CPU time (user + system, children included), as docs/fuzzing-and-sanitizers.md
# reports them.
timed() {
  local TIMEFORMAT="timing: $1: %0R s wall, %0U s user + %0S s system CPU"
  shift
  time "$@"
}

# Configures and builds the ASan+UBSan+libFuzzer tree (clang, -O1): the test
# suite, the CLI, the fuzz targets and their seed corpora. `targets` narrows it.
build_asan() {
  CC=clang CXX=clang++ cmake -S "$root" -B "$asan_dir" -G Ninja -DCMAKE_BUILD_TYPE=Sanitize \
    -DCMAKE_CXX_FLAGS_SANITIZE="-O1 -gline-tables-only" -DCMAKE_C_FLAGS_SANITIZE="-O1 -gline-tables-only" \
    -DCROWDPROF_SANITIZE=address,undefined -DCROWDPROF_FUZZ=ON >/dev/null
  cmake --build "$asan_dir" -j"$jobs" ${targets:+--target $targets}
}

# explain_failures DIR [TEST_DIR]: after a failed `ctest --test-dir TEST_DIR ...
# >DIR/ctest.log` (TEST_DIR: DIR unless given), prints ctest's summary, then
# each failed test's own output (why, not only which), then runs the failed
# tests once more and says whether they fail again: a failure that does not come
# back is still a failure, but a different one to look for.
explain_failures() {
  local dir=$1 test_dir=${2:-$1}
  sed -n '/% tests passed/,$p' "$dir/ctest.log"
  echo "--- the failed tests' output:"
  "$root/tests/ci/failed_output.sh" "$dir/ctest.log"
  if ctest --test-dir "$test_dir" --rerun-failed --output-on-failure >"$dir/ctest-rerun.log" 2>&1; then
    echo "--- run again alone, the failed tests passed: a failure that depends on timing or on the tests beside it"
  else
    echo "--- run again alone, they failed again:"
    "$root/tests/ci/failed_output.sh" "$dir/ctest-rerun.log" | head -n 30
  fi
}

# lsan_crash_only DIR: after a failed `ctest ... >DIR/ctest.log`, true when every
# failed test's output shows LeakSanitizer itself crashing at a process's exit
# ("Tracer caught signal 11 ... LeakSanitizer has encountered a fatal error":
# its stop-the-world tracer; no leak was found, LSan could not look), whether in
# the test's own process or in a crowdprof it ran (whose exit status and stderr
# the crash then changes, so the test's own checks fail too), and no other
# sanitizer report, and they pass when run again with leak detection off, so
# that ASan and UBSan still check them. Says so, naming them. A sanitizer
# report, or a failure again, is false: the stage fails.
lsan_crash_only() {
  local dir=$1 log=$1/ctest.log names=() name section
  mapfile -t names < <(sed -n 's/^[[:space:]]*[0-9]* - \(.*\) (Failed)$/\1/p' "$log")
  ((${#names[@]} > 0)) || return 1
  # Every test ctest lists as failed failed as "Failed": a timeout, a crash or
  # an abort is not a tracer's death at exit.
  (($(sed -n '/The following tests FAILED:/,$p' "$log" | grep -Ec '^[[:space:]]*[0-9]+ - ') == ${#names[@]})) || return 1
  for name in "${names[@]}"; do
    section=$(awk -v n="$name" '
      $0 ~ ("Test +#[0-9]+: " n " ") { show = 1; next }
      /^ *[0-9]+\/[0-9]+ Test +#|^ *Start +[0-9]+: |^[0-9]+% tests passed/ { show = 0 }
      show' "$log")
    grep -q "LeakSanitizer has encountered a fatal error" <<<"$section" || return 1
    if grep -Eq "ERROR: AddressSanitizer|ERROR: LeakSanitizer: detected|runtime error" <<<"$section"; then return 1; fi
  done
  local pattern
  pattern="^($(IFS='|'; echo "${names[*]}"))\$"
  ASAN_OPTIONS="$ASAN_OPTIONS:detect_leaks=0" ctest --test-dir "$dir" -R "$pattern" --output-on-failure \
    >"$dir/ctest-no-lsan.log" 2>&1 || return 1
  # ... and every one of them ran again (a pattern that matched fewer proves nothing).
  grep -q "100% tests passed, 0 tests failed out of ${#names[@]}\$" "$dir/ctest-no-lsan.log" || return 1
  echo "sanitize: LeakSanitizer crashed at the exit of ${names[*]} (its tracer, not a leak); run again with leak detection off, ASan and UBSan found nothing"
}
