#!/usr/bin/env bash
# frustum cpu against frustum gpu (docs/modes.md, "The GPU-driven crowd") at
# 1,000, 10,000 and 100,000 copies of the default character in mode baked, with
# two cameras: `close` (about a dozen copies on screen whatever the crowd, so the
# drawing is the same at every size) and one turned away from the crowd (nothing
# on screen: what is left is the per-copy work). Prints one markdown row per run:
# the categories' medians (ms), the frame, the bytes sent and the draws. Not run
# by CI: about two minutes on the 2-core machine; its times depend on the machine.
# Usage: tests/scripts/measure_gpu_cull.sh CROWDPROF
# Environment: SIZES ("1000 10000 100000"), FRAMES (30), WARMUP (5), OUT (a new
#   temporary folder; kept: one JSON result per run). Needs python3.
set -euo pipefail

crowdprof=${1:?usage: measure_gpu_cull.sh CROWDPROF}
scene=$(cd "$(dirname "$0")/../.." && pwd)/scenes/humanoid.glb
out=${OUT:-$(mktemp -d)}
mkdir -p "$out"
echo "| camera | copies | frustum | on screen | Logic | Scenegraph | Rasterizer | Overhead | frame | bytes sent | draws |"
echo "|---|---|---|---|---|---|---|---|---|---|---|"
for camera in close 0,1,5000,0,1,6000; do
  for n in ${SIZES:-1000 10000 100000}; do
    for frustum in cpu gpu; do
      json=$out/${camera//,/_}-$n-$frustum.json
      "$crowdprof" bench "$scene" -n "$n" --mode baked --frustum "$frustum" --camera "$camera" --backend auto \
        --resolution 320x180 --frames "${FRAMES:-30}" --warmup "${WARMUP:-5}" --json "$json" >/dev/null
      python3 - "$json" "$camera" "$n" "$frustum" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
c, k = r["categories"], r["counters"]
ms = lambda name: f'{c[name + "_ms"]["median_ms"]:.3f}'
print(f'| {sys.argv[2]} | {int(sys.argv[3]):,} | {sys.argv[4]} | {k["copies_visible"]} | {ms("logic")} | '
      f'{ms("scenegraph")} | {ms("rasterizer")} | {ms("overhead")} | {r["frame"]["median_ms"]:.3f} | '
      f'{k["bytes_uploaded"]} | {k["draw_calls"]} |')
PY
    done
  done
done
echo "results: $out" >&2
