#!/usr/bin/env bash
# The numbers of docs/rendering.md and docs/performance.md for the GPU skinning
# modes of issue 12 (threaded and hwskin for reference, buffer, instanced, compute,
# baked): 160 and 1,000 copies
# of scenes/humanoid.glb drawn at 1600x900 with the default backend (llvmpipe
# without a GPU), median frame, the CPU categories, draw calls, bytes uploaded,
# GPU memory, bake time and deviation, and the GPU timer when the result has one.
# Not run by CI; about 2 minutes on the 2-core machine.
#
#   tests/scripts/measure_gpu_skinning.sh [CROWDPROF]   (default build/crowdprof)
#   MODES="threaded hwskin buffer instanced compute baked" COPIES="160 1000" OUT=folder for the JSON
set -euo pipefail
cd "$(dirname "$0")/../.."
bin=${1:-build/crowdprof}
modes=${MODES:-threaded hwskin buffer instanced compute baked}
copies_list=${COPIES:-160 1000}
out=${OUT:-$(mktemp -d)}
mkdir -p "$out"
for copies in $copies_list; do
  frames=20 warmup=3
  ((copies >= 1000)) && frames=6 warmup=1
  for mode in $modes; do
    setsid "$bin" bench scenes/humanoid.glb -n "$copies" --mode "$mode" --backend auto --frames "$frames" \
      --warmup "$warmup" --json "$out/$mode-$copies.json" >/dev/null
  done
done
python3 - "$out" "$copies_list" "$modes" <<'PY'
import json, sys
out, copies_list, modes = sys.argv[1], sys.argv[2].split(), sys.argv[3].split()
print("| mode | copies | frame ms | Animations | Rasterizer | GPU Latency | GPU ms | draws | bytes/frame | GPU bytes | bake ms | deviation |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|")
for copies in copies_list:
    for mode in modes:
        r = json.load(open(f"{out}/{mode}-{copies}.json"))
        c, k, g = r["categories"], r["counters"], r.get("gpu_skinning", {})
        gpu = r.get("gpu_time", {}).get("median_ms") if isinstance(r.get("gpu_time"), dict) else None
        dev = (f'{g["max_deviation"]:.4g} ({100 * g["max_deviation_fraction"]:.3f}% of height)'
               if "max_deviation" in g else "")
        print(f'| {mode} | {copies} | {r["frame"]["median_ms"]:.1f} | {c["animations_ms"]["median_ms"]:.1f} | '
              f'{c["rasterizer_ms"]["median_ms"]:.1f} | {c["gpu_latency_ms"]["median_ms"]:.1f} | '
              f'{"n/a" if gpu is None else f"{gpu:.2f}"} | {k["draw_calls"]} | {k["bytes_uploaded"]} | '
              f'{g.get("gpu_bytes", "")} | {g.get("bake_ms", "") and round(g["bake_ms"], 1)} | {dev} |')
print(f"renderer: {r['environment']['renderer']}; JSON in {out}")
PY
