#!/usr/bin/env bash
# ./setup.sh fuzz [SECONDS] [TARGET...]: runs each libFuzzer target of tests/fuzz
# for SECONDS (default 60) on the ASan+UBSan build, starting from the committed
# corpus (tests/fuzz/corpus/TARGET, where the last long run stopped) and the
# seeds the build makes, with the target's dictionary (tests/fuzz/dictionaries),
# and growing a corpus in build-sanitize/fuzz/corpus/TARGET: the committed one is
# copied there first, so the source tree stays as it was. A crash,
# leak, timeout or sanitizer report stops with the input saved in
# build-sanitize/fuzz/artifacts/TARGET/ (minimise it with -minimize_crash=1, fix,
# and keep it in tests/fuzz/regressions/TARGET/). Prints, per target, the
# executions, coverage (edges) and features reached. FUZZ_MERGE=1 then merges
# what the run found into tests/fuzz/corpus/TARGET (-merge=1: the smallest set of
# inputs that reaches every feature of the committed corpus and the run's), for a
# long run whose ground CI should start from; commit the result if it stays
# under 1 MB (FUZZ_MERGE_LARGEST=BYTES merges only inputs up to that size). FUZZ_SEED fixes libFuzzer's
# random seed (the sanitizer stage of CI sets it, so that a finding there is the
# same on every run of the same code); unset, each run explores anew.
# FUZZ_RUNS=N stops each target after N executions instead (SECONDS 0: no time
# limit), for issue 28's long runs of 1,000,000 executions per target.
set -euo pipefail
source "$(dirname "$0")/common.sh"

seconds=${1:-60}
shift || true
[[ $seconds =~ ^[0-9]+$ ]] || { echo "usage: ./setup.sh fuzz [SECONDS] [TARGET...]" >&2; exit 2; }
names=("$@")
((${#names[@]})) || names=(gltf_loader result_reader result_tools scene_file)

targets="fuzz_seeds ${names[*]/#/fuzz_}"
build_asan >/dev/null

status=0
for name in "${names[@]}"; do
  corpus=$asan_dir/fuzz/corpus/$name
  artifacts=$asan_dir/fuzz/artifacts/$name
  log=$asan_dir/fuzz/$name.log
  mkdir -p "$corpus" "$artifacts"
  committed=$root/tests/fuzz/corpus/$name
  if [[ -d $committed ]]; then cp -n "$committed"/* "$corpus"/ 2>/dev/null || true; fi
  options=(-dict="$root/tests/fuzz/dictionaries/$name.dict")
  # The loader's inputs are capped just above its largest seed (the humanoid,
  # 40 KiB, at one action of six keys): a lower cap cuts that seed and reaches
  # fewer features.
  [[ $name == gltf_loader ]] && options+=(-max_len=49152)
  [[ -n ${FUZZ_RUNS:-} ]] && options+=(-runs="$FUZZ_RUNS")
  # -timeout: a single input that takes this long is a hang worth fixing.
  # -rss_limit_mb: the loader refuses files past 1 GiB; more memory is a finding.
  if ! "$asan_dir/tests/fuzz/fuzz_$name" -max_total_time="$seconds" -timeout=25 -rss_limit_mb=2560 "${options[@]}" \
      -print_final_stats=1 -seed="${FUZZ_SEED:-0}" -artifact_prefix="$artifacts/" "$corpus" "$asan_dir/fuzz/seeds/$name" >"$log" 2>&1; then
    status=1
    echo "fuzz: $name FAILED, see $log and $artifacts/" >&2
    grep -E "ERROR|SUMMARY|fuzz: " "$log" | head -5 >&2 || true
  fi
  if [[ ${FUZZ_MERGE:-0} == 1 ]]; then
    merged=$asan_dir/fuzz/merged/$name
    inputs=$asan_dir/fuzz/merge-inputs/$name
    rm -rf "$merged" "$inputs" && mkdir -p "$merged" "$inputs" "$committed"
    # FUZZ_MERGE_LARGEST=BYTES merges only inputs up to that size, to keep the
    # committed corpus under 1 MB (a long run's whole corpus is far larger).
    find "$committed" "$corpus" -type f -size -$((${FUZZ_MERGE_LARGEST:-1073741824} + 1))c \
      -exec cp -n {} "$inputs"/ \;
    "$asan_dir/tests/fuzz/fuzz_$name" -merge=1 "${options[@]}" -timeout=25 -rss_limit_mb=2560 \
      "$merged" "$inputs" >"$asan_dir/fuzz/$name.merge.log" 2>&1
    rm -rf "$committed" && mv "$merged" "$committed"
    echo "fuzz: $name: merged into tests/fuzz/corpus/$name: $(ls "$committed" | wc -l) inputs, $(cat "$committed"/* | wc -c) bytes"
  fi
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
  done_line=$(grep -E '^#[0-9]+' "$log" | tail -1)
  cov=$(sed -n 's/.* cov: \([0-9]*\).*/\1/p' <<<"$done_line")
  ft=$(sed -n 's/.* ft: \([0-9]*\).*/\1/p' <<<"$done_line")
  elapsed=$(sed -n 's/^Done [0-9]* runs in \([0-9]*\) second.*/\1/p' "$log")
  echo "fuzz: $name: ${runs:-?} executions in ${elapsed:-$seconds} s, coverage ${cov:-?} edges, ${ft:-?} features, corpus $(ls "$corpus" | wc -l) inputs"
done
exit $status
