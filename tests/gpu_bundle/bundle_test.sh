#!/usr/bin/env bash
# The GPU bundle, here on llvmpipe: made from the build tree, self-contained
# (run from a copy elsewhere with the build's libraries out of reach of its
# RPATH), it runs two GPU modes at a small size and writes parseable results;
# without ALLOW_SOFTWARE it refuses llvmpipe; it will not write into a folder
# it did not make.
set -Eeuo pipefail
source_dir=$(realpath "$1") build_dir=$(realpath "$2")
work=$build_dir/gpu-bundle-test
fail() { echo "bundle_test: $*" >&2; exit 1; }
trap 'echo "bundle_test: line $LINENO: \"$BASH_COMMAND\" failed (status $?)" >&2' ERR
rm -rf "$work" && mkdir -p "$work"

# A user's folder that is not a bundle is left alone.
mkdir "$work/mine" && echo keep >"$work/mine/notes.txt"
if "$source_dir/tests/gpu_bundle/make.sh" "$build_dir" "$work/mine" 2>"$work/refused.err"; then fail "make.sh wrote into a folder that is not a bundle"; fi
grep -q "is not a bundle" "$work/refused.err" || fail "no reason given: $(cat "$work/refused.err")"
[[ $(cat "$work/mine/notes.txt") == keep ]] || fail "the user's file changed"

"$source_dir/tests/gpu_bundle/make.sh" "$build_dir" "$work/bundle" >"$work/make.log"
mv "$work/bundle" "$work/moved"  # nothing in it may point back at the build tree
bundle=$work/moved
for file in bin/crowdprof run.sh lib/libEGL.so.1 lib/libtbb.so.12 scenes/humanoid.glb; do
  [[ -e $bundle/$file ]] || fail "the bundle lacks $file"
done
(($(du -sm "$bundle" | cut -f1) <= 64)) || fail "the bundle is over 64 MiB"

if ! EGL_PLATFORM=surfaceless "$bundle/run.sh" "$work/refuse" >/dev/null 2>"$work/refuse.err"; then
  if grep -q "software rasteriser" "$work/refuse.err"; then :
  elif grep -q "EGL gives no GL context" "$work/refuse.err"; then echo "bundle_test: skipped: no EGL here"; exit 77
  else fail "run.sh failed otherwise: $(cat "$work/refuse.err")"; fi
else fail "run.sh measured on llvmpipe without ALLOW_SOFTWARE"
fi

ALLOW_SOFTWARE=1 SIZES=12 PASSES="1 3" MODES="instanced baked+frustum=gpu nosuchmode" FRAMES=2 WARMUP=0 "$bundle/run.sh" "$work/out" >"$work/run.log" 2>&1 ||
  fail "run.sh failed: $(tail -5 "$work/run.log")"
python3 - "$work/out/results.json" <<'PY'
import json, sys
results = json.load(open(sys.argv[1]))
assert "llvmpipe" in results["renderer"], results["renderer"]
runs = results["runs"]
assert len(runs) == 6, runs
assert runs[0]["mode"] == "instanced" and runs[0]["environment"]["backend"] == "egl", runs[0]["environment"]
assert runs[0]["frame"]["median_ms"] > 0
# A mode with a switch, as compare spells it, runs as --mode baked --frustum gpu.
assert runs[1]["switches"]["skinning"] == "baked" and runs[1]["switches"]["frustum"] == "gpu", runs[1]
assert runs[1]["counters"]["draw_calls"] == 1, runs[1]["counters"]
assert runs[2]["mode"] == "nosuchmode" and "expected one of" in runs[2]["error"], runs[2]
assert runs[3]["mode"].startswith("instanced") and runs[3]["switches"]["passes"] == 3, runs[3]["switches"]
passes = [p["pass"] for p in runs[3]["gpu_time"]["passes"]]
assert passes == ["skinning", "prepass", "shadows", "colour"], passes
PY
grep -q '^| instanced | 12 | 1 | [0-9.]*[mu]s |' "$work/out/summary.md" || fail "no row for instanced: $(cat "$work/out/summary.md")"
grep -q '^| instanced | 12 | 3 | [0-9.]*[mu]s |.*| skinning [0-9.]*[mu]s, prepass' "$work/out/summary.md" ||
  fail "no row for instanced with passes: $(cat "$work/out/summary.md")"
grep -q '^| nosuchmode | 12 | 1 | exit 2' "$work/out/summary.md" || fail "the failed run has no row"
grep -q '^gpu-run: GL_VENDOR Mesa' "$work/run.log" || fail "no GL_VENDOR line: $(head -5 "$work/run.log")"
# Each row ends with the index order, the colour pass's vertex reuse and the bytes a copy.
grep -q '^| instanced | 12 | 1 | .*| optimized | [0-9.]* | [0-9.]* | 16.0 |$' "$work/out/summary.md" ||
  fail "no index order, vertex reuse, bytes or 16-byte records in instanced's row: $(cat "$work/out/summary.md")"
[[ -s $work/out/runs/baked_frustum_gpu-12-p1.json ]] || fail "no file for baked+frustum=gpu: $(ls "$work/out/runs")"
# A switch without a value is refused before any run, saying why.
if ALLOW_SOFTWARE=1 SIZES=12 MODES="baked+frustum" "$bundle/run.sh" "$work/novalue" >/dev/null 2>"$work/novalue.err"; then
  fail "a MODES entry with a switch but no value ran"
fi
grep -q "needs a value" "$work/novalue.err" || fail "no reason for the refused MODES entry: $(cat "$work/novalue.err")"
# Past its budget the script records the runs it did not make.
ALLOW_SOFTWARE=1 SIZES=12 MODES=hwskin BUDGET=0 "$bundle/run.sh" "$work/budget" >/dev/null 2>&1 || fail "a spent budget failed the script"
grep -q '^| hwskin | 12 | 4 | not run: the 0 s budget was spent' "$work/budget/summary.md" || fail "no row for the run not made: $(cat "$work/budget/summary.md")"
[[ -s $work/out/report.html ]] || fail "no HTML report"
# A second run into the same folder replaces its own files; a foreign folder is refused.
ALLOW_SOFTWARE=1 SIZES=12 MODES=hwskin FRAMES=1 WARMUP=0 "$bundle/run.sh" "$work/out" >/dev/null 2>&1 || fail "a rerun into its own folder failed"
[[ ! -e $work/out/runs/instanced-12-p1.json ]] || fail "the rerun kept the earlier run's files"
if ALLOW_SOFTWARE=1 "$bundle/run.sh" "$work/mine" >/dev/null 2>&1; then fail "run.sh wrote into the user's folder"; fi
[[ $(ls "$work/mine") == notes.txt ]] || fail "run.sh changed the user's folder"
rm -rf "$work"
echo "bundle_test: made, moved, refused llvmpipe, ran on it when allowed"
