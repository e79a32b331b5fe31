#!/usr/bin/env bash
# A bundle's run (made by ./setup.sh gpu-bundle DIR): every GPU mode, and
# threaded (CPU skinning, drawn) for reference, at 160, 10,000 and 100,000
# copies of the humanoid (69 bones, 4,951 vertices) through EGL on the GPU,
# drawn once a frame and with 4 passes (depth prepass, 2 shadow cascades,
# colour: --passes).
#   run.sh OUT_DIR
# Writes into OUT_DIR (new, or one this script wrote before):
#   runs/MODE-N-pP.json|.txt|.err  each bench's result, its table, its stderr
#   results.json                every run's result (or why it has none), with the renderer
#   report.html                 crowdprof report of every run that finished
#   summary.md                  one row per run: frame, Animations, Rasterizer, GPU time and
#                               its split by pass, index order, the colour pass's invocations
#                               per vertex drawn, the bytes sent a copy on screen and how many
#                               of them are per-copy records
# Each run has a time limit (LIMIT, seconds, default 60): one that is cut off,
# refused or failed is a row that says so, and the script goes on, so that it
# fits a call of 10 minutes; once BUDGET seconds (default 540) have gone, the
# runs left are rows that say they were not run. It refuses to measure when the renderer is a
# software rasteriser (llvmpipe, softpipe, swrast): bundled loader libraries can
# make a run fall back silently. ALLOW_SOFTWARE=1 lifts that (the bundle's test).
# Environment: MODES ("hwskin hwskin+index_order=file buffer instanced
# instanced+index_order=file compute baked baked+frustum=gpu threaded": the
# GPU-skinned modes in both index orders; a mode may carry switches as compare
# spells them), SIZES
# ("160 10000 100000"), PASSES ("1 4"), LIMIT (60), BUDGET (540), FRAMES and
# WARMUP (by size: 120/5 at 160, 30/3 to 10,000, 8/2 above).
set -uo pipefail
bundle=$(cd "$(dirname "$0")" && pwd)
out=${1:?usage: run.sh OUT_DIR}
fail() { echo "gpu-run: $*" >&2; exit 1; }
if [[ -e $out ]]; then
  [[ -d $out && (-z $(ls -A "$out") || -f $out/summary.md || -d $out/runs) ]] ||
    fail "$out exists and was not written by run.sh: choose a new folder"
fi
mkdir -p "$out/runs" || fail "cannot make $out/runs"
rm -f "$out"/runs/* "$out/results.json" "$out/report.html" "$out/summary.md"

export LD_LIBRARY_PATH=$bundle/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
# glvnd's libEGL finds the driver's vendor library through a JSON file; a
# container often keeps NVIDIA's under /usr/local/nvidia.
if [[ -z ${__EGL_VENDOR_LIBRARY_FILENAMES:-} ]] && ! ls /usr/share/glvnd/egl_vendor.d/*.json /etc/glvnd/egl_vendor.d/*.json >/dev/null 2>&1; then
  for vendor in /usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json /usr/local/share/glvnd/egl_vendor.d/10_nvidia.json; do
    [[ -f $vendor ]] && export __EGL_VENDOR_LIBRARY_FILENAMES=$vendor && break
  done
fi
crowdprof=$bundle/bin/crowdprof
scene=$bundle/scenes/humanoid.glb
"$crowdprof" --version >/dev/null 2>"$out/version.err" || fail "the bundled crowdprof does not start here: $(head -c 300 "$out/version.err")"

# Which renderer EGL gives, before anything is measured.
probe=$("$crowdprof" bench "$scene" -n 4 --frames 1 --warmup 0 --backend egl --mode hwskin 2>"$out/probe.err") ||
  fail "EGL gives no GL context: $(head -c 300 "$out/probe.err")"
renderer=$(sed -n 's/^renderer \(.*\) | [0-9]* draw calls.*/\1/p' <<<"$probe")
echo "gpu-run: $("$crowdprof" --version)"
echo "gpu-run: renderer $renderer"
echo "gpu-run: GL_VENDOR $(sed -n 's/.*, GL_VENDOR \(.*\))$/\1/p' <<<"$renderer")"
if grep -Eqi 'llvmpipe|softpipe|swrast|software' <<<"$renderer" && [[ ${ALLOW_SOFTWARE:-0} != 1 ]]; then
  fail "the renderer is a software rasteriser ($renderer), not the GPU: is the driver's EGL vendor library visible? (__EGL_VENDOR_LIBRARY_FILENAMES)"
fi

read -r -a modes <<<"${MODES:-hwskin hwskin+index_order=file buffer instanced instanced+index_order=file compute baked baked+frustum=gpu threaded}"
for mode in "${modes[@]}"; do
  IFS='+' read -r -a parts <<<"$mode"
  for switch in "${parts[@]:1}"; do
    [[ $switch == ?*=?* ]] || fail "MODES entry '$mode': '$switch' needs a value, as in baked+frustum=gpu"
  done
done
read -r -a sizes <<<"${SIZES:-160 10000 100000}"
read -r -a pass_counts <<<"${PASSES:-1 4}"
limit=${LIMIT:-60} budget=${BUDGET:-540}
json_text() { sed 's/\\/\\\\/g; s/"/\\"/g' | tr -d '\000-\037' | head -c 400; }
{
  echo "| mode | copies | passes | frame | Animations | Rasterizer | GPU time | GPU by pass | wall s | index order | invocations per vertex, colour | bytes a copy on screen | of them records |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|"
} >"$out/summary.md"
entries=()
for n in "${sizes[@]}"; do
  if ((n <= 160)); then frames=${FRAMES:-120} warmup=${WARMUP:-5}
  elif ((n <= 10000)); then frames=${FRAMES:-30} warmup=${WARMUP:-3}
  else frames=${FRAMES:-8} warmup=${WARMUP:-2}; fi
  for passes in "${pass_counts[@]}"; do
  for mode in "${modes[@]}"; do
    run=$out/runs/${mode//[+=]/_}-$n-p$passes
    # baked+frustum=gpu: --mode baked --frustum gpu.
    IFS='+' read -r -a parts <<<"$mode"
    mode_args=(--mode "${parts[0]}")
    for switch in "${parts[@]:1}"; do
      name=${switch%%=*}
      mode_args+=("--${name//_/-}" "${switch#*=}")
    done
    if ((SECONDS >= budget)); then
      entries+=("{\"mode\": \"$mode\", \"copies\": $n, \"passes\": $passes, \"error\": \"not run: the ${budget} s budget was spent\"}")
      echo "| $mode | $n | $passes | not run: the ${budget} s budget was spent ||||| 0 |||||" >>"$out/summary.md"
      continue
    fi
    start=$SECONDS
    timeout --kill-after=5 "$limit" "$crowdprof" bench "$scene" -n "$n" "${mode_args[@]}" --backend egl --passes "$passes" \
      --frames "$frames" --warmup "$warmup" --json "$run.json" >"$run.txt" 2>"$run.err"
    status=$? wall=$((SECONDS - start))
    if ((status == 0)) && [[ -s $run.json ]]; then
      entries+=("$(cat "$run.json")")
      # Each figure as the table prints it, with its unit (ms or us).
      figure() { sed -n "s/^$1 *: *\([0-9.]*[mu]s\).*/\1/p" "$run.txt"; }
      gpu=$(figure 'GPU time')
      by_pass=$(sed -n 's/^GPU passes : \(.*\)   medians.*/\1/p' "$run.txt" | sed 's/ | /, /g')
      # The order the triangles were drawn in, the colour pass's vertex reuse (the
      # last column of the statistics' row) and the bytes sent a copy on screen.
      order=$(sed -n 's/.*"index_order": *"\([a-z]*\)".*/\1/p' "$run.json" | head -1)
      reuse=$(awk '/^invocations per vertex drawn/ {print $NF}' "$run.txt")
      bytes=$(sed -n 's/.*"bytes_uploaded_per_copy_on_screen": *\([0-9.e+]*\).*/\1/p' "$run.json" | head -1)
      records=$(sed -n 's/.*"record_bytes_per_copy_on_screen": *\([0-9.e+]*\).*/\1/p' "$run.json" | head -1)
      echo "| $mode | $n | $passes | $(figure Frametime) | $(figure Animations) | $(figure Rasterizer) | ${gpu:-n/a} | ${by_pass:-n/a} | $wall | ${order:-file} | ${reuse:-n/a} | ${bytes:-n/a} | ${records:-n/a} |" >>"$out/summary.md"
    else
      if ((status == 124 || status == 137)); then why="cut off after the ${limit} s limit"
      else why="exit $status: $(tr '\n' ' ' <"$run.err" | head -c 300)"; fi
      rm -f "$run.json"
      entries+=("{\"mode\": \"$mode\", \"copies\": $n, \"passes\": $passes, \"error\": \"$(json_text <<<"$why")\"}")
      echo "| $mode | $n | $passes | $why ||||| $wall |||||" >>"$out/summary.md"
    fi
    echo "gpu-run: $mode at $n copies, $passes passes: ${wall} s, exit $status"
  done
  done
done
{
  echo "{\"bundle\": \"crowdprof GPU run\", \"version\": \"$("$crowdprof" --version | json_text)\","
  echo " \"renderer\": \"$(json_text <<<"$renderer")\", \"runs\": ["
  for i in "${!entries[@]}"; do
    ((i > 0)) && echo ","
    echo "${entries[$i]}"
  done
  echo "]}"
} >"$out/results.json"
finished=("$out"/runs/*.json)
if [[ -f ${finished[0]} ]]; then
  "$crowdprof" report "${finished[@]}" -o "$out/report.html" 2>"$out/report.err" ||
    echo "gpu-run: no HTML report: $(head -c 300 "$out/report.err")" >&2
fi
cat "$out/summary.md"
echo "gpu-run: results in $out"
