#!/usr/bin/env bash
# Regenerates the README's figures from this build (./setup.sh docs): the
# Results table (compare of the thesis's CPU modes on the default scene, the
# median of RUNS processes with their spread), the work a frame does (digest
# and counters: the same on every machine, which tests/cli/readme_figures_test.cpp
# holds the README to), and docs/report-bench.png (the HTML report of a bench,
# in Debian's chromium). It states the machine, the date, the commit and the
# load average before and after, so a reader can tell a quiet run from a busy one.
#   docs/figures.sh BUILD_DIR        (RUNS, default 5)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:?usage: docs/figures.sh BUILD_DIR}
bin=$build/crowdprof
runs=${RUNS:-5}
[[ -x $bin ]] || { echo "figures: no $bin: build first (./setup.sh build)" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
scene=scenes/humanoid.glb

load_before=$(cut -d' ' -f1-3 /proc/loadavg)
for ((r = 1; r <= runs; ++r)); do
  "$bin" compare "$scene" -n 160 --backend none --modes master,culled,threaded --threads 1 --frames 240 --warmup 20 \
    -q --json "$work/one-$r.json"
  "$bin" compare "$scene" -n 160 --backend none --modes master,threaded --threads 2 --frames 240 --warmup 20 \
    -q --json "$work/two-$r.json"
done
# Both arithmetics' digests (skinning fuses multiply-adds on AVX2 and up): a
# machine without AVX2 cannot make the first.
"$bin" --simd AVX2 bench "$scene" -n 160 --mode threaded --backend none --frames 10 --warmup 0 -q \
  --json "$work/work.json" || { echo "figures: needs a CPU with AVX2 for the fused digest" >&2; exit 2; }
"$bin" --simd SSE4 bench "$scene" -n 160 --mode threaded --backend none --frames 10 --warmup 0 -q \
  --json "$work/work-sse4.json"
load_after=$(cut -d' ' -f1-3 /proc/loadavg)
"$bin" bench "$scene" -n 160 --frames 120 -q --html "$work/bench.html"
if command -v chromium >/dev/null; then
  chromium --headless --no-sandbox --disable-gpu --hide-scrollbars --window-size=1280,1400 \
    --screenshot="$work/report-bench.png" "file://$work/bench.html" >/dev/null 2>&1
  [[ -s $work/report-bench.png ]] && cp "$work/report-bench.png" docs/report-bench.png
else
  echo "figures: no chromium: docs/report-bench.png left as it was" >&2
fi

python3 - "$work" "$runs" "$load_before" "$load_after" "$("$bin" --version)" <<'PY'
import json, re, statistics, subprocess, sys, datetime
work, runs, before, after, version = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4], sys.argv[5]
def summary(kind, r):
    return {m["mode"]: m for m in json.load(open(f"{work}/{kind}-{r}.json"))["summary"]}
rows = []
for label, kind, mode in [("master", "one", "master"), ("culled", "one", "culled"),
                          ("threaded, 1 thread", "one", "threaded"), ("threaded, 2 threads", "two", "threaded")]:
    per_run = [summary(kind, r) for r in range(1, runs + 1)]
    frame = [s[mode]["frame_median_ms"] for s in per_run]
    anim = [s[mode]["categories_median_ms"]["animations_ms"] for s in per_run]
    rast = [s[mode]["categories_median_ms"]["rasterizer_ms"] for s in per_run]
    ratio = [s["master"]["frame_median_ms"] / s[mode]["frame_median_ms"] for s in per_run]
    med = statistics.median
    rows.append(f"| {label} | {med(frame):.2f} ({min(frame):.2f}–{max(frame):.2f}) | {med(anim):.2f} | "
                f"{med(rast):.2f} | {med(ratio):.2f}× |")
work_json = json.load(open(f"{work}/work.json"))
sse4_json = json.load(open(f"{work}/work-sse4.json"))
c = work_json["counters"]
cpu = next((l.split(":", 1)[1].strip() for l in open("/proc/cpuinfo") if l.startswith("model name")), "unknown CPU")
cores = subprocess.run(["nproc"], capture_output=True, text=True).stdout.strip()
today = datetime.date.today().isoformat()
block = f"""<!-- figures:begin (made by docs/figures.sh: ./setup.sh docs) -->
{version}, on {cores} cores of an {cpu}, {today}; load average {before} before
the runs and {after} after. `compare scenes/humanoid.glb -n 160 --backend none`, 240
frames after 20, medians of {runs} processes (min–max of the frame's medians):

| mode | frame ms | Animations ms | Rasterizer ms | ratio to master |
|---|---|---|---|---|
""" + "\n".join(rows) + f"""

The work of a frame is the same on every machine:
`bench scenes/humanoid.glb -n 160 --mode threaded --frames 10 --warmup 0` updates
{c['poses_updated']} poses and skins {c['vertices_skinned']:,} vertices a frame ({c['copies_visible']} copies on
screen, {c['copies_culled']} culled), digest `{work_json['digest']}` on CPUs with AVX2 (fused
multiply-adds), `{sse4_json['digest']}` on SSE4 and below.
<!-- figures:end -->"""
readme = open("README.md").read()
new, n = re.subn(r"<!-- figures:begin.*?<!-- figures:end -->", lambda m: block, readme, flags=re.S)
if n != 1:
    sys.exit("figures: README.md has no figures block (<!-- figures:begin --> ... <!-- figures:end -->)")
open("README.md", "w").write(new)
print(block)
PY
