#!/usr/bin/env bash
# The CPU pose + skinning measurements of docs/performance.md (issue 17): mode
# threaded with culling off (every copy posed and skinned), 1 and 2 threads,
# shared and random actions, 160, 1,000 and 10,000 copies of scenes/humanoid.glb
# (and, shared, with --vertex-format packed);
# each configuration run REPS times, binaries interleaved, median frame of each
# run, then the median of those medians. Then the thesis scene's two-thread
# speed-up measured side by side in one process: COMPARES runs of `compare`
# (1 thread, i.e. the plain serial loop, against 2, interleaved in blocks of 10
# frames), each run's ratio of median frames and their median, the figure to
# quote (separate processes catch the host's noise at different moments). About
# 2 minutes on the 2-core machine with REPS=3.
#
#   bench/measure_cpu.sh [NEW] [OLD]
#     NEW  crowdprof to measure (default build/crowdprof)
#     OLD  a crowdprof from before, run side by side (optional); e.g. one built
#          from before the change being measured, with the build options it
#          defaulted to then
#   REPS=3 (runs per configuration), COMPARES=9 (0: skip them), OUT=folder for the JSON (default a temp dir)
#   NEW_ARGS, OLD_ARGS: global options for each binary, e.g. to compare store
#          policies with one binary: OLD_ARGS="--stores regular" NEW_ARGS=
#          "--stores auto" bench/measure_cpu.sh build/crowdprof build/crowdprof
#   RT=1   run each configuration under SCHED_FIFO (chrt -f 10, needs root): on
#          a machine other jobs load, a two-thread run then gets both cores
#          (it takes them from the other jobs for the few seconds it runs)
#
# Each run gets its own scheduling group (setsid): with autogroup on, `nice`
# alone does not keep other jobs off a two-thread run. Other tenants still add
# noise: compare the two binaries' columns, which shared it.
set -euo pipefail
cd "$(dirname "$0")/.."
new=${1:-build/crowdprof}
old=${2:-}
reps=${REPS:-3}
out=${OUT:-$(mktemp -d)}
mkdir -p "$out"
scene=scenes/humanoid.glb
binaries=(new)
rt=()
[[ ${RT:-0} == 1 ]] && rt=(chrt -f 10)
read -r -a new_args <<<"${NEW_ARGS:-}"
read -r -a old_args <<<"${OLD_ARGS:-}"
[[ -n $old ]] && binaries+=(old)

# copies:frames:warm-up, so that each run lasts about the same.
sizes=(160:240:20 1000:60:6 10000:12:2)
for ((rep = 1; rep <= reps; rep++)); do
  for threads in 1 2; do
    for actions in shared random; do
      for size in "${sizes[@]}"; do
        IFS=: read -r copies frames warmup <<<"$size"
        for which in "${binaries[@]}"; do
          bin=$new args=("${new_args[@]}")
          [[ $which == old ]] && bin=$old args=("${old_args[@]}")
          setsid "${rt[@]}" "$bin" "${args[@]}" bench "$scene" -n "$copies" --mode threaded --culling off --threads "$threads" \
            --actions "$actions" --seed 7 --frames "$frames" --warmup "$warmup" \
            --json "$out/$which-$threads-$actions-$copies-$rep.json" >/dev/null
        done
        # --vertex-format packed (10 bytes a vertex instead of 24), new binary, shared actions.
        if [[ $actions == shared ]]; then
          setsid "${rt[@]}" "$new" "${new_args[@]}" bench "$scene" -n "$copies" --mode threaded --culling off --threads "$threads" \
            --actions "$actions" --seed 7 --frames "$frames" --warmup "$warmup" --vertex-format packed \
            --json "$out/packed-$threads-$actions-$copies-$rep.json" >/dev/null
        fi
      done
    done
  done
  echo "measure_cpu: pass $rep of $reps done" >&2
done

python3 - "$out" "$reps" "${binaries[@]}" <<'EOF'
import json, statistics, sys
out, reps, binaries = sys.argv[1], int(sys.argv[2]), sys.argv[3:]
def median_ms(which, threads, actions, copies):
    runs = [json.load(open(f"{out}/{which}-{threads}-{actions}-{copies}-{r}.json")) for r in range(1, reps + 1)]
    vertices = runs[0]["scene"]["vertices"]
    return statistics.median(r["frame"]["median_ms"] for r in runs), vertices, runs[0]["environment"].get("simd", "?")
head = "| threads | actions | copies |"
for b in binaries:
    head += f" {b} ms | {b} µs/copy | {b} GB/s |"
if len(binaries) == 2:
    head += " old / new |"
print(head)
print("|" + "---|" * (head.count("|") - 1))
one = {}
for threads in (1, 2):
    for actions in ("shared", "random"):
        for copies in (160, 1000, 10000):
            row = f"| {threads} | {actions} | {copies:,} |"
            ms = {}
            for b in binaries:
                m, vertices, simd = median_ms(b, threads, actions, copies)
                ms[b] = m
                # Skinned output: positions and normals, 2 x 12 bytes a vertex.
                gbs = copies * vertices * 24 / (m * 1e-3) / 1e9
                row += f" {m:.3f} | {m * 1000 / copies:.2f} | {gbs:.1f} |"
            if len(binaries) == 2:
                row += f" {ms['old'] / ms['new']:.2f}× |"
            one[(threads, actions, copies)] = ms
            print(row)
print()
for b in binaries:
    for actions in ("shared", "random"):
        for copies in (160, 1000, 10000):
            s = one[(1, actions, copies)][b] / one[(2, actions, copies)][b]
            print(f"{b}: {actions}, {copies:,} copies: 2 threads {s:.2f}× faster than 1")
    for threads in (1, 2):
        for actions in ("shared", "random"):
            r = (one[(threads, actions, 10000)][b] / 10000) / (one[(threads, actions, 160)][b] / 160)
            print(f"{b}: {threads} thread(s), {actions}: cost per copy at 10,000 copies {r:.2f}× that at 160")
print("\n| threads | copies | float ms | packed ms | packed GB/s (10 B a vertex) | float / packed |")
print("|---|---|---|---|---|---|")
for threads in (1, 2):
    for copies in (160, 1000, 10000):
        f = one[(threads, "shared", copies)]["new"]
        p, vertices, _ = median_ms("packed", threads, "shared", copies)
        gbs = copies * vertices * 10 / (p * 1e-3) / 1e9
        print(f"| {threads} | {copies:,} | {f:.3f} | {p:.3f} | {gbs:.1f} | {f / p:.2f}× |")
print(f"\nJSON in {out}; SIMD target: {median_ms(binaries[0], 1, 'shared', 160)[2]}")
EOF

# The thesis scene's two-thread speed-up, side by side in one process.
compares=${COMPARES:-9}
((compares > 0)) || exit 0
for actions in shared random; do
  ratios=()
  for ((run = 1; run <= compares; run++)); do
    setsid "${rt[@]}" "$new" "${new_args[@]}" compare "$scene" -n 160 --actions "$actions" --seed 7 \
      --modes threaded+culling=off+parallel=off,threaded+culling=off --threads 2 --frames 240 --warmup 20 \
      --backend none -q --json "$out/compare-$actions-$run.json"
    ratios+=("$(python3 -c 'import json, sys; r = json.load(open(sys.argv[1]))["runs"]; print(round(r[0]["frame"]["median_ms"] / r[1]["frame"]["median_ms"], 3))' "$out/compare-$actions-$run.json")")
  done
  printf '%s\n' "${ratios[@]}" | python3 -c '
import statistics, sys
r = sorted(float(x) for x in sys.stdin)
print(f"new, interleaved in one process: {sys.argv[1]}, 160 copies: 2 threads {statistics.median(r):.2f}x faster"
      f" than 1 (median of {len(r)} compares; runs {r[0]:.2f} to {r[-1]:.2f})")' "$actions"
done
