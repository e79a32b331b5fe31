#!/usr/bin/env bash
# Counts the instructions a bench spends under the Animations clock, per frame,
# with callgrind (not run by CI; about a minute). Instruction counts do not
# move with the machine's load, so they tell a change to the per-frame work
# apart from noise where timings cannot (issue 13: the thesis scene under mode
# `shared`). Everything timed under Animations runs inside
# CrowdBench::update_poses on the frame's thread; with more than one thread,
# the work that workers take (PoseUpdater's update_state, skin_range) is added, never the
# time a thread spends waiting (callgrind runs one thread at a time, so waits
# spin a number of times that depends on its scheduling).
#   Prints: instructions per frame under Animations, then the largest parts.
# Usage: tests/scripts/callgrind_animations.sh CROWDPROF [BENCH OPTIONS...]
#   default options: -n 160 --actions shared --mode shared --threads 1
#   --frames 100 --warmup 10 --backend none (the thesis scene, every frame
#   evaluating a new state). Frames counted: warmup + frames.
# Environment: SCENE (scenes/humanoid.glb), OUT (a new temporary folder; kept:
#   callgrind's files). Needs valgrind. Valgrind hides AVX-512 from the program,
#   so skinning runs on its AVX2 kernels (CROWDPROF_SIMD=AVX2 makes that explicit).
set -euo pipefail

crowdprof=${1:?usage: callgrind_animations.sh CROWDPROF [BENCH OPTIONS...]}
shift
scene=${SCENE:-$(cd "$(dirname "$0")/../.." && pwd)/scenes/humanoid.glb}
out=${OUT:-$(mktemp -d /tmp/callgrind_animations.XXXXXX)}
options=("$@")
[[ ${#options[@]} -gt 0 ]] || options=(-n 160 --actions shared --mode shared --threads 1 --frames 100 --warmup 10)

command -v valgrind >/dev/null || { echo "callgrind_animations: needs valgrind (apt-get install valgrind)" >&2; exit 2; }
[[ -x $crowdprof ]] || { echo "callgrind_animations: $crowdprof is not an executable" >&2; exit 2; }
[[ -f $scene ]] || { echo "callgrind_animations: no scene $scene (set SCENE)" >&2; exit 2; }
mkdir -p "$out"

# Frames stepped: --frames and --warmup as given, else the bench's defaults.
frames=120 warmup=10
for ((i = 0; i < ${#options[@]}; ++i)); do
  case ${options[i]} in
    --frames) frames=${options[i + 1]} ;;
    --warmup) warmup=${options[i + 1]} ;;
  esac
done
stepped=$((frames + warmup))

CROWDPROF_SIMD=AVX2 valgrind --tool=callgrind --separate-threads=yes --callgrind-out-file="$out/cg.out" \
  "$crowdprof" bench "$scene" --backend none -q "${options[@]}" >"$out/valgrind.log" 2>&1 ||
  { cat "$out/valgrind.log" >&2; exit 4; }

# Inclusive instructions of the functions whose name matches $2 in file $1.
inclusive() {
  callgrind_annotate --inclusive=yes --threshold=100 "$1" 2>/dev/null |
    awk -v pattern="$2" '$0 ~ pattern { gsub(",", "", $1); sum += $1 } END { printf "%.0f\n", sum }'
}

# One file per thread (cg.out-01 the frame's thread, then the workers).
total=0
for file in "$out"/cg.out-*; do
  if [[ $file == *-01 ]]; then pattern=':crowdprof::CrowdBench::update_poses\('
  else pattern=':crowdprof::PoseUpdater::(update_state|skin_range)\('; fi
  total=$((total + $(inclusive "$file" "$pattern")))
done
main=$out/cg.out-01
echo "callgrind_animations: ${options[*]}: $((total / stepped)) instructions per frame under Animations ($stepped frames)"
# Parts called only from the frame (the skinning and pose jobs are also run
# at load, for the crowd's bounds, so they are told apart by their callers).
per_frame() { echo $(($(inclusive "$main" ":crowdprof::$1") / stepped)); }
plan=$(per_frame 'UpdatePlanner::plan\(')
state=$(per_frame 'PoseUpdater::update_state\(')
skin=$(per_frame 'PoseUpdater::skin_vertices\(')
echo "  on the frame's thread, per frame: the plan $plan (PoseSharing::take $(per_frame 'PoseSharing::take\('), release $(per_frame 'PoseSharing::release\(')),"
echo "    evaluations $((state + $(per_frame 'PoseUpdater::skin_range\('))) (skinning $skin, the rest: sampling, model and skinning matrices)"
echo "  callgrind's files: $out"
