#!/usr/bin/env bash
# Measures every mode crowdprof has (the thesis's four, buffer, instanced, and any
# later preset: the list is read from the binary) with a GL backend at 160 and
# 1,000 copies of the default character, and prints one markdown row per mode and
# size: median frame, the CPU categories that carry time, CPU time, the GPU's own
# time from GL timer queries, and the counters that explain them. Not run by CI:
# it takes about a minute on a quiet 2-core machine with llvmpipe, and its numbers
# depend on the machine and its load.
# Usage: tests/scripts/measure_gpu_modes.sh CROWDPROF
# Environment: SCENE (scenes/humanoid.glb), SIZES ("160 1000"), MODES (all
#   presets, comma-separated), FRAMES (20 at 160 copies, 8 above), WARMUP (3),
#   BACKEND (auto), RESOLUTION (1600x900, the thesis's), OUT (a new temporary
#   folder; kept: one JSON result per run).
# Needs jq.
set -euo pipefail

crowdprof=${1:?usage: measure_gpu_modes.sh CROWDPROF}
scene=${SCENE:-$(cd "$(dirname "$0")/../.." && pwd)/scenes/humanoid.glb}
sizes=${SIZES:-160 1000}
warmup=${WARMUP:-3}
backend=${BACKEND:-auto}
resolution=${RESOLUTION:-1600x900}
out=${OUT:-$(mktemp -d /tmp/measure_gpu_modes.XXXXXX)}

command -v jq >/dev/null || { echo "measure_gpu_modes: needs jq (apt-get install jq)" >&2; exit 2; }
[[ -x $crowdprof ]] || { echo "measure_gpu_modes: $crowdprof is not an executable" >&2; exit 2; }
[[ -f $scene ]] || { echo "measure_gpu_modes: no scene $scene (set SCENE)" >&2; exit 2; }
mkdir -p "$out"

# Every preset, as the binary names them when refusing an unknown mode.
if [[ -z ${MODES:-} ]]; then
  MODES=$( ("$crowdprof" bench "$scene" --mode '?' 2>&1 || true) | sed -n "s/.*expected one of //p" | tr -d ' ')
  [[ -n $MODES ]] || { echo "measure_gpu_modes: cannot read the mode list from $crowdprof" >&2; exit 2; }
fi
IFS=, read -r -a modes <<<"$MODES"

echo "# $("$crowdprof" --version)"
echo "# $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg), scene $(basename "$scene"), $resolution, backend $backend, warm-up $warmup"
echo
echo "| mode | copies | frame ms | Animations ms | Rasterizer ms | GPU Latency ms | CPU ms | GPU time ms | draw calls | bytes uploaded | palette bytes on GPU | fallbacks |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
start=$SECONDS
for n in $sizes; do
  frames=${FRAMES:-$((n <= 160 ? 20 : 8))}
  for mode in "${modes[@]}"; do
    json=$out/$mode-$n.json
    if ! "$crowdprof" bench "$scene" -n "$n" --mode "$mode" --backend "$backend" --resolution "$resolution" \
        --frames "$frames" --warmup "$warmup" -q --json "$json" 2>"$out/$mode-$n.err"; then
      echo "| $mode | $n | failed: $(head -c 200 "$out/$mode-$n.err") |||||||||"
      continue
    fi
    jq -r --arg mode "$mode" --arg n "$n" '
      def ms: if . == null then "n/a" else (. * 100 | round / 100 | tostring) end;
      "| \($mode) | \($n) | \(.frame.median_ms | ms) | \(.categories.animations_ms.median_ms | ms) | \(.categories.rasterizer_ms.median_ms | ms) | \(.categories.gpu_latency_ms.median_ms | ms) | \(.cpu.median_ms | ms) | \(if .gpu_time.available then (.gpu_time.median_ms | ms) else "n/a (" + .gpu_time.reason + ")" end) | \(.counters.draw_calls) | \(.counters.bytes_uploaded) | \(.counters.gpu_palette_bytes // 0) | \(.counters.copies_fallback) |"' "$json"
  done
done
echo
echo "# $((SECONDS - start)) s; results in $out"
