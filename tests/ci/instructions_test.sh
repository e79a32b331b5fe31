#!/usr/bin/env bash
# check --metric instructions, asserting on counts (they do not move with the
# machine) and on errors: a stored baseline of instructions per frame, the same
# run checked against it passes, a run with more copies (--timings-only: other
# settings) fails, a baseline counted otherwise is refused (exit 3), and the
# timed metrics cannot be mixed in (exit 2). Skipped (77) where neither a
# hardware counter nor valgrind can count.
set -Eeuo pipefail
source_dir=$(realpath "$1") crowdprof=$(realpath "$2")
work=$(dirname "$crowdprof")/instructions-test
fail() { echo "instructions_test: $*" >&2; exit 1; }
trap 'echo "instructions_test: line $LINENO: \"$BASH_COMMAND\" failed (status $?)" >&2' ERR
rm -rf "$work" && mkdir -p "$work"
scene=$source_dir/scenes/humanoid.glb

# valgrind stops at RDTSCP on CPUs without it: libhwy's static initialiser,
# which runs one, must call the binary's own TimerResolution instead
# (lib/measuring/valgrind_safe_start.cpp), or nothing here can count on such a host.
bindings=$(LD_DEBUG=bindings "$crowdprof" --version 2>&1 >/dev/null)
grep -q "libhwy.* to .*crowdprof \[0\]: normal symbol \`_ZN3hwy8platform15TimerResolutionEv'" <<<"$bindings" ||
  fail "libhwy's TimerResolution is not bound to the binary's own: valgrind would stop at RDTSCP where the CPU lacks it"
run=(-n 6 --frames 3 --warmup 1 --mode threaded)

status=0
"$crowdprof" check "$scene" "${run[@]}" --metric instructions --baseline "$work/base.json" --update-baseline \
  2>"$work/record.err" >"$work/record.out" || status=$?
if ((status != 0)); then
  grep -q "nothing counts instructions here" "$work/record.err" && { echo "instructions_test: skipped: $(cat "$work/record.err")"; exit 77; }
  fail "recording failed (exit $status): $(cat "$work/record.err")"
fi
python3 - "$work/base.json" <<'PY'
import json, sys
i = json.load(open(sys.argv[1]))["instructions"]
assert i["source"] in ("perf_event", "callgrind") and i["threads"] == 1, i
assert i["per_frame"] > 100000, i  # six copies skinned: far more than a few instructions
assert len(i["runs"]) == 1 and i["simd"], i
PY

status=0
"$crowdprof" check --baseline "$work/base.json" --metric instructions --junit "$work/same.xml" >"$work/same.out" 2>&1 || status=$?
((status == 0)) || fail "the same run failed (exit $status): $(cat "$work/same.out")"
grep -q "^instructions per frame: .*no change" "$work/same.out" || fail "no verdict line: $(cat "$work/same.out")"
grep -q "^work: the same" "$work/same.out" || fail "no work line: $(cat "$work/same.out")"
python3 - "$work/same.xml" <<'PY'
import sys, xml.etree.ElementTree as ET
suites = ET.parse(sys.argv[1]).getroot()
assert [c.get("name") for c in suites.iter("testcase")] == ["instructions", "work"] and suites.get("failures") == "0"
PY

# 8 copies instead of 6: a third more work per frame, caught by the count alone.
status=0
"$crowdprof" check --baseline "$work/base.json" --metric instructions -n 8 --timings-only >"$work/more.out" 2>&1 || status=$?
((status == 1)) || fail "more work passed (exit $status): $(cat "$work/more.out")"
grep -q "SLOWER" "$work/more.out" || fail "no SLOWER: $(cat "$work/more.out")"

# A count from another source, SIMD target or compiler is not compared.
python3 - "$work/base.json" "$work/other.json" <<'PY'
import json, sys
doc = json.load(open(sys.argv[1]))
doc["instructions"]["simd"] = "SSE4"
json.dump(doc, open(sys.argv[2], "w"))
PY
status=0
(cd "$work" && "$crowdprof" check --baseline other.json --metric instructions >"$work/other.out" 2>&1) || status=$?
((status == 3)) || fail "a baseline of another SIMD target was compared (exit $status): $(cat "$work/other.out")"
grep -q "counts compare only from the same source, SIMD target and compiler" "$work/other.out" || fail "$(cat "$work/other.out")"

status=0
"$crowdprof" check --baseline "$work/base.json" --metric instructions,frame 2>"$work/mixed.err" || status=$?
((status == 2)) && grep -q "instructions is a metric of its own" "$work/mixed.err" || fail "mixed metrics: $(cat "$work/mixed.err")"
rm -rf "$work"
echo "instructions_test: recorded, passed unchanged, caught more work, refused another origin and mixed metrics"
