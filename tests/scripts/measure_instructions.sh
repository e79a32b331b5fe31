#!/usr/bin/env bash
# Measures the instruction metric (check --metric instructions; issue 25 item
# 2; not run by CI): the spread of instructions per frame over RUNS (20)
# processes of an unchanged build, then whether 1%, 2% and 5% more copies (all
# on screen, so the work follows the copies) are caught at the default 1%
# tolerance.
# Usage: tests/scripts/measure_instructions.sh CROWDPROF
# Environment: N (160), SCENE (scenes/humanoid.glb), FRAMES (20), WARMUP (2),
#   RUNS (20), OUT (a new temporary folder; kept).
# Needs jq, and valgrind where the host has no hardware counters.
set -euo pipefail
crowdprof=$(realpath "${1:?usage: measure_instructions.sh CROWDPROF}")
n=${N:-160}
scene=${SCENE:-$(cd "$(dirname "$0")/../.." && pwd)/scenes/humanoid.glb}
out=${OUT:-$(mktemp -d /tmp/measure_instructions.XXXXXX)}
mkdir -p "$out"
run=("$scene" --mode threaded --camera all --frames "${FRAMES:-20}" --warmup "${WARMUP:-2}" --metric instructions)
start=$SECONDS
"$crowdprof" check "${run[@]}" -n "$n" --runs "${RUNS:-20}" --baseline "$out/base.json" --update-baseline -q
echo "# $("$crowdprof" --version); $(jq -r '.instructions | "\(.source), SIMD \(.simd), \(.compiler)"' "$out/base.json")"
jq -r '.instructions.runs | "spread over \(length) processes: min \(min), max \(max), (max-min)/min \((max - min) / min * 100)%"' "$out/base.json"
echo "# $((SECONDS - start)) s for the baseline's runs"
for more in 1 2 5; do
  m=$(((n * (100 + more) + 50) / 100))
  status=0
  "$crowdprof" check "${run[@]}" -n "$m" --baseline "$out/base.json" --timings-only >"$out/more-$more.txt" 2>&1 || status=$?
  echo "$more% more copies (-n $m): exit $status: $(head -1 "$out/more-$more.txt")"
done
