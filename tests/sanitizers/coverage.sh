#!/usr/bin/env bash
# ./setup.sh coverage: line coverage of lib/ by the whole test suite. A GCC
# build with --coverage at -O0 (Debug, so every line that runs is a line gcov
# sees) in build-coverage (CROWDPROF_COVERAGE_DIR to change), every test of
# ctest on it (the ones that need chromium, debootstrap or a GPU skip as they
# do elsewhere), then gcovr over lib/ only: one summary line, a table per stage
# folder, and an HTML report with every file's lines in build-coverage/coverage/.
# Not in CI (it costs a second full build); see docs/fuzzing-and-sanitizers.md.
# Exits non-zero if the build or a test fails; the figures are still printed,
# marked as those of a failing suite.
set -euo pipefail
source "$(dirname "$0")/common.sh"
dir=${CROWDPROF_COVERAGE_DIR:-$root/build-coverage}
report=$dir/coverage

build_coverage() {
  CC=gcc CXX=g++ cmake -S "$root" -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=Debug \
    -DCMAKE_CXX_FLAGS_DEBUG="-O0 -g --coverage" -DCMAKE_C_FLAGS_DEBUG="-O0 -g --coverage" \
    -DCMAKE_EXE_LINKER_FLAGS=--coverage >/dev/null
  cmake --build "$dir" -j"$jobs"
  # A build folder reused across commits keeps the objects, and their .gcno, of
  # sources that are gone; gcovr would count them. Ninja forgets the objects it
  # no longer builds; their notes files go with them.
  ninja -C "$dir" -t cleandead >/dev/null
  find "$dir" -name '*.gcno' -print0 | while IFS= read -r -d '' notes; do
    [[ -e ${notes%.gcno}.o ]] || rm -f "$notes"
  done
}
echo "coverage: GCC --coverage -O0 build in $dir" >&2
timed "coverage build" build_coverage >/dev/null

# Counts from an earlier run would add to this one's.
find "$dir" -name '*.gcda' -delete
# Two tests cannot pass on an instrumented build, and do not run lib/ in a
# way the rest do not: install.tree builds a consumer without --coverage against
# the installed, instrumented libcrowdprof.a (the link lacks gcov's symbols),
# and gpu_bundle.llvmpipe refuses the bundle of instrumented -O0 binaries as over
# the 64 MiB a GPU machine's call carries.
not_here='^(install\.tree|gpu_bundle\.llvmpipe)$'
status=0
timed "coverage test suite" ctest --test-dir "$dir" -j"$jobs" -E "$not_here" --output-on-failure >"$dir/ctest.log" 2>&1 ||
  { status=$?; explain_failures "$dir"; echo "coverage: the test suite failed; the figures below are of a failing suite" >&2; }
tail -n 3 "$dir/ctest.log"

# Only the sources of lib/ (the filter is a path under the source tree, so
# tests/, cli/, bench/, the build folder's generated files and /usr are out).
# Objects that were compiled but never ran (no .gcda) count with zero lines run.
rm -rf "$report"
mkdir -p "$report"
cd "$root"
timed "gcovr" gcovr --root "$root" --filter "lib/" --object-directory "$dir" -j "$jobs" --gcov-ignore-parse-errors \
  --json-summary "$report/summary.json" --txt "$report/lines.txt" \
  --html-details "$report/index.html" --html-title "crowdprof: lib/ line coverage" "$dir"
python3 - "$report/summary.json" <<'EOF'
import json, sys
from collections import defaultdict
files = json.load(open(sys.argv[1]))["files"]
folders = defaultdict(lambda: [0, 0])
for f in files:
    parts = f["filename"].split("/")
    folder = "/".join(parts[:2]) if len(parts) > 2 else parts[0]
    folders[folder][0] += f["line_covered"]
    folders[folder][1] += f["line_total"]
def percent(covered, total):
    return f"{100.0 * covered / total:.1f}%" if total else "-"
covered = sum(c for c, _ in folders.values())
total = sum(t for _, t in folders.values())
print(f"lib/ line coverage: {percent(covered, total)} ({covered}/{total} lines)")
print(f"{'folder':<16} {'lines':>7} {'covered':>8} {'percent':>8}")
for folder in sorted(folders):
    c, t = folders[folder]
    print(f"{folder:<16} {t:>7} {c:>8} {percent(c, t):>8}")
EOF
echo "coverage: every file's lines in $report/index.html" >&2
exit "$status"
