#!/usr/bin/env bash
# --gbench-json on bench and compare: Google Benchmark's JSON, read by its own
# compare.py (Debian's libbenchmark-tools, with python3-scipy) as it reads a
# benchmark's: two crowdprof results compared, every family present, the U
# test run on the frames. Asserts on the format, never on a timing.
set -Eeuo pipefail
source_dir=$(realpath "$1") crowdprof=$(realpath "$2")
work=$(dirname "$crowdprof")/gbench-test
compare_py=/usr/share/benchmark/compare.py
fail() { echo "gbench_test: $*" >&2; exit 1; }
trap 'echo "gbench_test: line $LINENO: \"$BASH_COMMAND\" failed (status $?)" >&2' ERR
[[ -f $compare_py ]] || fail "$compare_py is missing: apt-get install libbenchmark-tools python3-scipy (./setup.sh test does)"
rm -rf "$work" && mkdir -p "$work"
scene=$source_dir/scenes/humanoid.glb
run=(-n 12 --frames 9 --warmup 1 -q)
"$crowdprof" bench "$scene" "${run[@]}" --mode threaded --gbench-json "$work/a.json"
"$crowdprof" bench "$scene" "${run[@]}" --mode threaded --gbench-json "$work/b.json"
"$crowdprof" compare "$scene" "${run[@]}" --modes master,threaded --sweep n=6 --gbench-json "$work/modes.json"

/usr/bin/python3 - "$work" <<'PY'
import json, sys
work = sys.argv[1]
a = json.load(open(work + "/a.json"))
assert a["context"]["library_build_type"] in ("release", "debug") and a["context"]["num_cpus"] >= 1
names = [b["name"] for b in a["benchmarks"]]
frame = "threaded/humanoid/n:12/frame"
iterations = [b for b in a["benchmarks"] if b["name"] == frame and b["run_type"] == "iteration"]
assert len(iterations) == 9 and [b["repetition_index"] for b in iterations] == list(range(9)), iterations
assert all(b["time_unit"] == "ms" and b["real_time"] > 0 and b["cpu_time"] > 0 for b in iterations)
assert frame + "_median" in names and frame + "_mean" in names and frame + "_stddev" in names, names
assert "threaded/humanoid/n:12/Animations" in names, names
modes = {b["run_name"] for b in json.load(open(work + "/modes.json"))["benchmarks"]}
for name in ("master/humanoid/n:12/frame", "threaded/humanoid/n:12/frame", "master/humanoid/n:6/frame"):
    assert name in modes, (name, sorted(modes))
PY

/usr/bin/python3 "$compare_py" benchmarks "$work/a.json" "$work/b.json" >"$work/compare.txt" 2>&1 ||
  fail "compare.py failed: $(cat "$work/compare.txt")"
grep -q "threaded/humanoid/n:12/frame " "$work/compare.txt" || fail "compare.py shows no frame: $(cat "$work/compare.txt")"
grep -q "threaded/humanoid/n:12/frame_pvalue" "$work/compare.txt" || fail "compare.py ran no U test: $(cat "$work/compare.txt")"
rm -rf "$work"
echo "gbench_test: bench and compare write Google Benchmark JSON that compare.py compares"
