#!/usr/bin/env bash
# Instructions per skinned vertex of each SIMD target's kernels, counted by
# callgrind (not run by CI; about a minute a target). Two runs a target, of
# FEW and FEW + 10 frames; the difference of their instructions inside
# SkinningJob::Run over the difference of their vertices skinned is the
# frames' own work (the end-of-run checks, which skin too, cancel out).
# Valgrind cannot run AVX-512, so the targets are AVX2 and below.
#   Usage: tests/scripts/callgrind_skinning_targets.sh CROWDPROF [TARGET...]
#   default targets: AVX2 SSE4 SSSE3 SCALAR.
# Environment: SCENE (scenes/humanoid.glb), COPIES (8).
set -euo pipefail
crowdprof=${1:?usage: callgrind_skinning_targets.sh CROWDPROF [TARGET...]}
shift
scene=${SCENE:-$(cd "$(dirname "$0")/../.." && pwd)/scenes/humanoid.glb}
copies=${COPIES:-8}
command -v valgrind >/dev/null || { echo "callgrind_skinning_targets: needs valgrind (apt-get install valgrind)" >&2; exit 2; }
[[ -x $crowdprof ]] || { echo "callgrind_skinning_targets: $crowdprof is not an executable" >&2; exit 2; }
[[ -f $scene ]] || { echo "callgrind_skinning_targets: no scene $scene (set SCENE)" >&2; exit 2; }
targets=("$@")
[[ ${#targets[@]} -gt 0 ]] || targets=(AVX2 SSE4 SSSE3 SCALAR)
out=$(mktemp -d /tmp/callgrind_skinning.XXXXXX)
trap 'rm -rf "$out"' EXIT

# count TARGET FRAMES -> "instructions vertices"
count() {
  CROWDPROF_SIMD=$1 valgrind --tool=callgrind --toggle-collect='crowdprof::SkinningJob::Run*' \
    --callgrind-out-file="$out/cg.out" "$crowdprof" bench "$scene" -n "$copies" --culling off --threads 1 \
    --frames "$2" --warmup 1 --json "$out/run.json" > /dev/null 2> "$out/valgrind.log" ||
    { cat "$out/valgrind.log" >&2; exit 1; }
  echo "$(sed -n 's/^totals: //p' "$out/cg.out") $(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["counters"]["vertices_skinned"])' "$out/run.json")"
}
echo "instructions per skinned vertex in SkinningJob::Run, $copies copies of $(basename "$scene"), culling off, one thread"
for target in "${targets[@]}"; do
  read -r i5 v5 <<< "$(count "$target" 5)"
  read -r i15 v15 <<< "$(count "$target" 15)"
  # vertices_skinned is per frame: 10 more frames skin 10 x that many more.
  python3 -c "import sys; print('%-7s %6.1f' % (sys.argv[1], (int(sys.argv[3]) - int(sys.argv[2])) / (10 * int(sys.argv[4]))))" "$target" "$i5" "$i15" "$v5"
done
