#!/usr/bin/env bash
# How much one unchanged scene's metrics move between processes and within one
# (not run by CI; about a minute on the 2-core machine, quiet): RUNS (12) separate
# `bench --calibrate` processes of FRAMES (120) frames, and one process of RUNS x
# FRAMES frames cut into RUNS blocks; for each metric, the median per frame of
# every process or block, their spread (max/min - 1) and their relative standard
# deviation, side by side. `check` samples processes (docs/compare-and-check.md)
# because the first spread is the larger, and gates on the metric that moves least.
# Usage: tests/scripts/measure_run_spread.sh CROWDPROF
# Environment: SCENE (scenes/humanoid.glb), N (160), MODE (threaded), THREADS
#   (the mode's default), FRAMES (120), WARMUP (10), RUNS (12), METRICS (samples
#   keys: "frame_ms cpu_ms animations_ms calibrated"; calibrated is a ratio, its
#   "ms" in the lines below are probes).
# Needs jq.
set -euo pipefail

crowdprof=${1:?usage: measure_run_spread.sh CROWDPROF}
scene=${SCENE:-$(cd "$(dirname "$0")/../.." && pwd)/scenes/humanoid.glb}
n=${N:-160}
mode=${MODE:-threaded}
frames=${FRAMES:-120}
warmup=${WARMUP:-10}
runs=${RUNS:-12}
read -r -a metrics <<<"${METRICS:-frame_ms cpu_ms animations_ms calibrated}"
threads=()
[[ -n ${THREADS:-} ]] && threads=(--threads "$THREADS")
command -v jq >/dev/null || { echo "measure_run_spread: needs jq (apt-get install jq)" >&2; exit 2; }
[[ -x $crowdprof ]] || { echo "measure_run_spread: $crowdprof is not an executable" >&2; exit 2; }
out=$(mktemp -d /tmp/measure_run_spread.XXXXXX)
echo "measure_run_spread: $("$crowdprof" --version); -n $n, mode $mode ${threads[*]}, $frames frames x $runs," \
  "${metrics[*]}; load $(cut -d' ' -f1-3 /proc/loadavg)"

# Median, spread and relative standard deviation of a JSON array of numbers.
stats='def med: sort | if length % 2 == 1 then .[length / 2 | floor] else (.[length / 2 - 1] + .[length / 2]) / 2 end;
  (add / length) as $mean | (map((. - $mean) * (. - $mean)) | add / (length - 1) | sqrt) as $sd
  | "median \(med * 1000 | round / 1000) ms, range \(min * 1000 | round / 1000)-\(max * 1000 | round / 1000) ms"
    + " (spread \((max / min - 1) * 1000 | round / 10)%), relative sd \($sd / $mean * 1000 | round / 10)%"'

for ((i = 1; i <= runs; ++i)); do
  "$crowdprof" bench "$scene" -n "$n" --mode "$mode" "${threads[@]}" --frames "$frames" --warmup "$warmup" -q \
    --calibrate --json "$out/run$i.json"
done
"$crowdprof" bench "$scene" -n "$n" --mode "$mode" "${threads[@]}" --frames $((frames * runs)) --warmup "$warmup" -q \
  --calibrate --json "$out/one.json"
for metric in "${metrics[@]}"; do
  jq -s "[.[] | .samples.$metric | sort | if length % 2 == 1 then .[length / 2 | floor] else (.[length / 2 - 1] + .[length / 2]) / 2 end] | $stats" \
    "$out"/run*.json | sed "s/^\"/$metric, separate processes: /; s/\"\$//"
  jq --argjson f "$frames" "[.samples.$metric as \$s | range(0; \$s | length; \$f) as \$i | \$s[\$i:\$i + \$f]
    | sort | if length % 2 == 1 then .[length / 2 | floor] else (.[length / 2 - 1] + .[length / 2]) / 2 end] | $stats" \
    "$out/one.json" | sed "s/^\"/$metric, blocks of one process: /; s/\"\$//"
done
rm -rf "$out"
