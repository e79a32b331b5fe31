#!/bin/bash
# crowdprof beside ozz-animation on the same work (issue 31), not in CI:
#   bench/ozz/compare_ozz.sh OZZ_SOURCE [PAIRS]
# Builds ozz-animation from OZZ_SOURCE (release 0.16, e.g. ../shared/ozz-animation-0.16)
# three times (-march=native, -mavx2 -mfma, -msse4.2), each with ozz_driver
# (bench/ozz/ozz_driver.cpp) linked against this checkout's library, then runs
# 160 copies of scenes/humanoid.glb, culling off, one thread: crowdprof at
# its best target, --simd AVX2 and --simd SSE4 against each ozz build, PAIRS
# (default 8) interleaved pairs of processes each. Prints per pair the
# crowdprof/ozz ratio of median frame times and the median and spread of the
# ratios, the work both counted (copies posed, vertices skinned) and how far
# ozz's vertices are from crowdprof's. ozz's SkinningJob does not renormalise
# the blended normals, which crowdprof's kernels do: the rows marked
# "+ renormalised" have ozz's driver do it after each job, so that both do the
# same work (and ozz's normals then lie within a rounding of crowdprof's).
# Then the same rows in one process each: ozz_driver runs crowdprof's jobs too
# (the library's, as the frame runs them), in blocks of 10 frames alternating
# with ozz's, so that the host's changes of speed between processes, which
# move the pairs' ratios, hit both alike.
# Then crossfades (issue 53), in one process each: every copy fading between
# two actions, `--crossfade sampled`'s work (two SamplingJobs, one context per
# copy per action, BlendingJob, LocalToModelJob; ozz_driver FADE sampled), on
# a generated locomotion character (`crowdprof gen --actions locomotion`) and
# the Fox (../shared/samples, skipped when absent). The generated character
# must come within 0.2 mm (the script stops otherwise); the Fox's keys lie
# far apart, where glTF's LINEAR (slerp, crowdprof) and ozz's normalised
# lerp part ways, so its distance is printed, not held to that bound.
# Needs ./setup.sh build done first.
# WORK (default /tmp/crowdprof-ozz) holds the builds; FRAMES (120) per run.
# Then the same fades with a third action laid over half the body by a joint
# mask (issue 56: ozz's partial blending, FADE layered), the mask's joint named.
# PART=fades runs the crossfades only, PART=layers the layered ones only (both
# build only the native and AVX2 ozz).
set -euo pipefail
ozz_source=$(realpath "${1:?usage: bench/ozz/compare_ozz.sh OZZ_SOURCE [PAIRS]}")
pairs=${2:-8}
frames=${FRAMES:-120}
root=$(cd "$(dirname "$0")/../.." && pwd)
work=${WORK:-/tmp/crowdprof-ozz}
crowdprof="$root/build/crowdprof"
scene="$root/scenes/humanoid.glb"
[ -x "$crowdprof" ] || { echo "compare_ozz.sh: $crowdprof is missing: run ./setup.sh build first" >&2; exit 2; }
[ -f "$ozz_source/include/ozz/animation/runtime/sampling_job.h" ] ||
  { echo "compare_ozz.sh: $ozz_source is not an ozz-animation source tree" >&2; exit 2; }
mkdir -p "$work"
cmake --install "$root/build" --prefix "$work/prefix" --component development > /dev/null
declare -A flags=([native]="-march=native" [avx2]="-mavx2 -mfma" [sse4]="-msse4.2")
part=${PART:-all}
variants="native avx2 sse4"
[ "$part" = fades ] || [ "$part" = layers ] && variants="native avx2"
for variant in $variants; do
  # Configured every time (cheap), so another OZZ_SOURCE is not ignored; built
  # incrementally: only the driver (and ozz) when they changed.
  cmake -S "$root/bench/ozz" -B "$work/$variant" -DCMAKE_BUILD_TYPE=Release -DOZZ_SOURCE="$ozz_source" \
    -DCMAKE_PREFIX_PATH="$work/prefix" -DCMAKE_CXX_FLAGS="${flags[$variant]}" > "$work/$variant.log" 2>&1 ||
    { cat "$work/$variant.log" >&2; exit 1; }
  cmake --build "$work/$variant" -j"$(nproc)" --target ozz_driver >> "$work/$variant.log" 2>&1 ||
    { tail -30 "$work/$variant.log" >&2; exit 1; }
done

crowdprof_run() {  # SIMD -> "median_ms poses vertices" of one crowdprof run
  local out="$work/run.json"
  CROWDPROF_SIMD="$1" "$crowdprof" bench "$scene" -n 160 --mode threaded --threads 1 --culling off \
    --actions shared --frames "$frames" --warmup 10 --json "$out" > /dev/null
  python3 -c 'import json,sys; r=json.load(open(sys.argv[1])); c=r["counters"]
print(r["frame"]["median_ms"], c["poses_updated"], c["vertices_skinned"])' "$out"
}
ozz_run() { "$work/$1/ozz_driver" "$scene" 160 "$frames" 10 "$2"; }  # VARIANT RENORMALISE
field() { python3 -c 'import json,sys; print(json.loads(sys.argv[1])[sys.argv[2]])' "$1" "$2"; }

best=$("$crowdprof" --version | sed -n 's/.*SIMD \([A-Z0-9_]*\).*/\1/p')
[ -n "$best" ] || { echo "compare_ozz.sh: no SIMD target in \`$crowdprof --version\`" >&2; exit 1; }

fade_rows() {  # crossfades, one process a row: sampled|layered SCENE...
  local fade=$1
  shift
  echo "Crossfades ($fade), 160 copies each fading every frame, one thread, sampling + blending +" \
    "local-to-model, 2 x $frames frames in blocks of 10 alternating"
  for scene_file in "$@"; do
    for row in "$best native" "AVX2 avx2"; do
      read -r simd variant <<< "$row"
      CROWDPROF_SIMD="$simd" "$work/$variant/ozz_driver" "$scene_file" 160 $((2 * frames)) 10 0 1 "$fade" |
        python3 -c 'import json, sys
r = json.load(sys.stdin)
r.update(variant=sys.argv[1], scene=sys.argv[2], mm=1000 * r["max_delta"], share=100 * r["max_delta_of_height"])
r["over"] = " under " + r["mask"] + " layered" if r["mask"] else ""
print("{scene}{over}: crowdprof {simd} / ozz {variant}: ratio median {ratio_median:.2f} (quartiles {ratio_q1:.2f}-"
      "{ratio_q3:.2f}); frame medians {crowdprof_median_ms:.3f} and {median_ms:.3f} ms; {poses_sampled} poses "
      "sampled, {joints_blended} joints blended a frame; ozz vertices within {mm:.3f} mm ({share:.4f}% of the "
      "height)".format(**r))
if r["mm"] > 0.2 and sys.argv[2] == "locomotion.glb":
    sys.exit("compare_ozz.sh: not the same fades: ozz vertices more than 0.2 mm away")' "$variant" "$(basename "$scene_file")"
    done
  done
}
fade_scenes=("$work/locomotion.glb")
"$crowdprof" gen -o "$work/locomotion.glb" --actions locomotion > /dev/null
fox="$root/../shared/samples/Fox/glTF-Binary/Fox.glb"
if [ -f "$fox" ]; then fade_scenes+=("$fox"); else echo "(no Fox at $fox: its crossfade rows skipped)"; fi
if [ "$part" = fades ] || [ "$part" = layers ]; then
  [ "$part" = fades ] && fade_rows sampled "${fade_scenes[@]}"
  fade_rows layered "${fade_scenes[@]}"
  exit 0
fi

echo "160 copies of $(basename "$scene"), culling off, one thread, $pairs interleaved pairs, $frames frames each"
for pair in "$best native 0" "AVX2 native 0" "AVX2 avx2 0" "SSE4 native 0" "SSE4 sse4 0" \
  "$best native 1" "AVX2 avx2 1" "SSE4 sse4 1"; do
  read -r simd variant renormalise <<< "$pair"
  ratios=()
  for ((i = 0; i < pairs; i++)); do
    read -r c poses vertices <<< "$(crowdprof_run "$simd")"
    o=$(ozz_run "$variant" "$renormalise")
    if [ "$poses" != "$(field "$o" poses_updated)" ] || [ "$vertices" != "$(field "$o" vertices_skinned)" ]; then
      echo "compare_ozz.sh: not the same work: crowdprof $poses poses, $vertices vertices; ozz $o" >&2
      exit 1
    fi
    ratios+=("$(python3 -c "print($c / $(field "$o" median_ms))")")
    printf '  crowdprof %-7s %.3f ms | ozz %-6s%s %.3f ms\n' "$simd" "$c" "$variant" \
      "$([ "$renormalise" = 1 ] && echo ' + renormalised')" "$(field "$o" median_ms)"
  done
  python3 - "$simd" "$variant" "$o" "${ratios[@]}" <<'PY'
import json, statistics, sys
simd, variant, last = sys.argv[1], sys.argv[2], json.loads(sys.argv[3])
r = sorted(float(x) for x in sys.argv[4:])
if last["renormalised"]:
    variant += f" + renormalised (normals within {last['max_normal_delta']:.2g} of crowdprof's)"
print(f"crowdprof {simd} / ozz {variant}: ratio median {statistics.median(r):.2f} (range {r[0]:.2f}-{r[-1]:.2f}); "
      f"both counted {last['poses_updated']} poses, {last['vertices_skinned']} vertices a frame; ozz's vertices within "
      f"{last['max_delta']:.2g} of crowdprof's ({100 * last['max_delta_of_height']:.3f}% of the height)")
PY
done

echo "In one process each, 2 x $frames frames in blocks of 10 alternating (ozz_driver INTERLEAVE)"
for row in "$best native 0" "AVX2 avx2 0" "SSE4 sse4 0" "$best native 1" "AVX2 avx2 1" "SSE4 sse4 1"; do
  read -r simd variant renormalise <<< "$row"
  CROWDPROF_SIMD="$simd" "$work/$variant/ozz_driver" "$scene" 160 $((2 * frames)) 10 "$renormalise" 1 |
    python3 -c 'import json, sys
r, variant = json.load(sys.stdin), sys.argv[1]
if r["renormalised"]: variant += " + renormalised"
q1, med, q3, ours, theirs, target = (r[k] for k in ("ratio_q1", "ratio_median", "ratio_q3",
                                                     "crowdprof_median_ms", "median_ms", "simd"))
print(f"crowdprof {target} / ozz {variant}: ratio median {med:.2f} (quartiles {q1:.2f}-{q3:.2f}); "
      f"frame medians {ours:.3f} and {theirs:.3f} ms")' "$variant"
done

fade_rows sampled "${fade_scenes[@]}"
fade_rows layered "${fade_scenes[@]}"
