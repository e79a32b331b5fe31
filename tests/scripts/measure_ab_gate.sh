#!/usr/bin/env bash
# Measures `crowdprof check --against` (the A/B of two builds, docs/ci.md) on
# this machine, as issue 25 item 6 asks (not run by CI: minutes, and its numbers
# depend on the machine):
#   self:   SELF (50) A/Bs of the binary against itself; every exit 1 is a
#           false alarm (goal: at most 1 of 50);
#   more10: DETECT (20) A/Bs where the current build animates and skins 10%
#           more copies than the base (the base is a wrapper that runs fewer
#           copies; --timings-only, as the work differs); every exit 1 is a
#           detection (goal: at least 19 of 20);
#   more5:  DETECT5 (20) of the same at 5% more copies (the rate is reported).
# With BUSY=1 another process keeps one core busy throughout (item 6d).
# Usage: tests/scripts/measure_ab_gate.sh CROWDPROF
# Environment: N (160), SCENE (scenes/humanoid.glb), CAMERA (all: every copy
#   on screen, so the work follows the copies), FRAMES (60), WARMUP (5),
#   AB_GROUPS (20), SELF (50), DETECT (20), DETECT5 (20), BUSY (0), OUT (a new
#   temporary folder; kept: every A/B's JSON and ab.csv).
# Needs jq. Prints one line per A/B and a summary per phase.
set -euo pipefail
crowdprof=$(realpath "${1:?usage: measure_ab_gate.sh CROWDPROF}")
n=${N:-160}
scene=${SCENE:-$(cd "$(dirname "$0")/../.." && pwd)/scenes/humanoid.glb}
out=${OUT:-$(mktemp -d /tmp/measure_ab_gate.XXXXXX)}
command -v jq >/dev/null || { echo "measure_ab_gate: needs jq (apt-get install jq)" >&2; exit 2; }
mkdir -p "$out"
args=("$scene" -n "$n" --mode threaded --camera "${CAMERA:-all}" --frames "${FRAMES:-60}" --warmup "${WARMUP:-5}"
  --groups "${AB_GROUPS:-20}" -q)

# A base that runs N/factor copies: the current build then does factor times the work.
wrapper() {
  local base_n=$1 file=$out/base-$1
  cat >"$file" <<WRAPPER
#!/usr/bin/env bash
args=()
while ((\$#)); do
  if [[ \$1 == -n || \$1 == --characters ]]; then args+=("\$1" "$base_n"); shift 2; else args+=("\$1"); shift; fi
done
exec "$crowdprof" "\${args[@]}"
WRAPPER
  chmod +x "$file"
  echo "$file"
}

busy_pid=
if [[ ${BUSY:-0} == 1 ]]; then
  (while :; do :; done) &
  busy_pid=$!
  trap 'kill $busy_pid 2>/dev/null' EXIT
fi

echo "phase,ab,exit,change,low,high,p,wall_s" >"$out/ab.csv"
phase() {
  local name=$1 count=$2 base=$3 alarms=0 i status
  shift 3
  for ((i = 1; i <= count; i++)); do
    status=0
    "$crowdprof" check "${args[@]}" --against "$base" --json "$out/$name-$i.json" "$@" || status=$?
    ((status <= 1)) || { echo "measure_ab_gate: check exited $status" >&2; exit 1; }
    alarms=$((alarms + status))
    jq -r --arg phase "$name" --arg i "$i" --arg status "$status" \
      '[$phase, $i, $status, .metrics[0].change, .metrics[0].change_low, .metrics[0].change_high, .metrics[0].p_adjusted, .wall_s] | @csv' \
      "$out/$name-$i.json" >>"$out/ab.csv"
    jq -r --arg phase "$name" --arg i "$i" --arg status "$status" \
      '"\($phase) \($i): exit \($status), change \(.metrics[0].change * 1000 | round / 10)% [\(.metrics[0].change_low * 1000 | round / 10), \(.metrics[0].change_high * 1000 | round / 10)], p \(.metrics[0].p_adjusted * 1000 | round / 1000), \(.wall_s | round) s"' \
      "$out/$name-$i.json"
  done
  echo "== $name: $alarms of $count exited 1"
}

echo "# $("$crowdprof" --version); $(nproc) cores; load $(cut -d' ' -f1-3 /proc/loadavg); busy core: ${BUSY:-0}"
echo "# $n copies, ${FRAMES:-60} frames after ${WARMUP:-5}, ${AB_GROUPS:-20} ABBA groups; results in $out"
phase self "${SELF:-50}" "$crowdprof"
phase more10 "${DETECT:-20}" "$(wrapper $(((n * 100 + 55) / 110)))" --timings-only
phase more5 "${DETECT5:-20}" "$(wrapper $(((n * 100 + 52) / 105)))" --timings-only
