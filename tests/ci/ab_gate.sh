#!/usr/bin/env bash
# CI's performance gate (docs/ci.md): the A/B of two builds of crowdprof at the
# same moment, with the files a CI system keeps.
#   ab_gate.sh BASE_BINARY CURRENT_BINARY OUT_DIR SCENE [check options...]
# Runs `CURRENT_BINARY check SCENE --against BASE_BINARY` and writes into
# OUT_DIR (made if missing): ab.json (both builds, every process, the verdict),
# junit.xml (a test case per metric and one for the work), summary.md (the
# verdict table; also appended to $GITHUB_STEP_SUMMARY when that is set) and
# report.html (a run of each build side by side).
# Exit status: check's. 0 passed; 1 slower or other work; 2 a bad option;
# 3 a bad input (the base binary, the scene); 4 a run failed; 130 interrupted.
set -uo pipefail
if (($# < 4)); then
  echo "usage: ab_gate.sh BASE_BINARY CURRENT_BINARY OUT_DIR SCENE [check options...]" >&2
  exit 2
fi
base=$1 current=$2 out=$3 scene=$4
shift 4
mkdir -p "$out" || exit 2
"$current" check "$scene" --against "$base" --json "$out/ab.json" --junit "$out/junit.xml" \
  --markdown "$out/summary.md" --html "$out/report.html" "$@"
status=$?
if [[ -n ${GITHUB_STEP_SUMMARY:-} && -f $out/summary.md ]]; then cat "$out/summary.md" >>"$GITHUB_STEP_SUMMARY"; fi
case $status in
  0) echo "ab_gate: passed" ;;
  1) echo "ab_gate: FAILED: slower, or the work changed (the table above; $out/junit.xml)" >&2 ;;
  *) echo "ab_gate: check could not judge (exit $status; the line above says why)" >&2 ;;
esac
exit "$status"
