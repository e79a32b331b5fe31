#!/usr/bin/env bash
# Issue 13, item 5: the capacity of the default character at a 16.7 ms budget
# (60 fps), per mode, with `crowdprof capacity` (not run by CI: its numbers
# depend on the machine and its load). --backend none: the CPU's side of a frame.
# Two cameras: the default one (the thesis's framing: most of a large crowd is
# off-screen, so culling modes skip it) and `all` (every copy on screen, so
# every copy is posed and skinned).
# Usage: tests/scripts/measure_capacity.sh CROWDPROF
#   CROWDPROF  the crowdprof binary (e.g. build/crowdprof)
# Environment: SCENE (scenes/humanoid.glb), BUDGET (16.7), MODES (default:
#   master, threaded and those of shared, budget that this build has), CAMERAS
#   ("default"; "default all" adds every copy on screen), FRAMES (60), WARMUP (10), PRECISION (0.05), MAX (100000),
#   OUT (a new temporary folder; kept: capacity-CAMERA.json and .svg).
# About two minutes per camera under load (most of it building the capped
# modes' crowds of tens of thousands); less on a quiet machine. Prints each table and a
# summary line per mode and camera: fits_n and its median, over_n and its median.
set -euo pipefail

crowdprof=${1:?usage: measure_capacity.sh CROWDPROF}
scene=${SCENE:-$(cd "$(dirname "$0")/../.." && pwd)/scenes/humanoid.glb}
budget=${BUDGET:-16.7}
frames=${FRAMES:-60}
warmup=${WARMUP:-10}
precision=${PRECISION:-0.05}
max=${MAX:-100000}
cameras=${CAMERAS:-default}
out=${OUT:-$(mktemp -d /tmp/measure_capacity.XXXXXX)}

command -v jq >/dev/null || { echo "measure_capacity: needs jq (apt-get install jq)" >&2; exit 2; }
[[ -x $crowdprof ]] || { echo "measure_capacity: $crowdprof is not an executable" >&2; exit 2; }
[[ -f $scene ]] || { echo "measure_capacity: no scene $scene (set SCENE)" >&2; exit 2; }
mkdir -p "$out"

if [[ -z ${MODES:-} ]]; then
  # The presets of issue 13 where this build has them (an unknown mode is exit 2).
  MODES=master,threaded
  for preset in shared budget lod; do
    if "$crowdprof" bench "$scene" -n 1 --frames 1 --warmup 0 -q --mode "$preset" >/dev/null 2>&1; then
      MODES+=,$preset
    fi
  done
fi

echo "crowdprof capacity: $scene, budget $budget ms, modes $MODES, $frames frames per point after $warmup warm-up"
echo "machine: $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg), $("$crowdprof" --version)"
for camera in $cameras; do
  echo
  echo "== camera $camera"
  start=$SECONDS
  "$crowdprof" capacity "$scene" --budget "$budget" --modes "$MODES" --camera "$camera" --backend none \
    --frames "$frames" --warmup "$warmup" --precision "$precision" --max-characters "$max" \
    --json "$out/capacity-$camera.json" --svg "$out/capacity-$camera.svg"
  echo "($((SECONDS - start)) s)"
done

echo
echo "summary (camera, mode, threads, fits_n, its median ms, over_n, its median ms, capped):"
for camera in $cameras; do
  jq -r --arg camera "$camera" '.modes[] | [$camera, .mode, .threads,
      (.largest_fit.characters // 0), (.largest_fit.median_ms // null | if . then (. * 1000 | round / 1000) else "-" end),
      (.first_over.characters // "-"), (.first_over.median_ms // null | if . then (. * 1000 | round / 1000) else "-" end), .capped] | @tsv' "$out/capacity-$camera.json"
done
echo "files: $out"
