#!/usr/bin/env bash
# tests/ci/ab_gate.sh and check --against, asserting on the work and the
# formats, never on a timed verdict (the machine is shared):
#  - the same binary twice: exit 0 (a 1000% tolerance: timing cannot fail it),
#    JUnit read by a real XML parser, Markdown, the A/B JSON with both builds;
#  - against a base wrapped to run twice the copies (other work of the
#    frame's own kind): exit 1, the work's test case failed, the command that
#    reproduces it (the current build is always this binary: check runs
#    itself, so the wrapper is the base);
#  - bad base builds (missing, not executable, not crowdprof, writing what this
#    build cannot read): exit 3, one line naming it, nothing run or written;
#  - a stored baseline's check writes the same JUnit and Markdown;
#  - docs/ci.md's workflow is YAML and calls ab_gate.sh verbatim.
set -Eeuo pipefail
source_dir=$(realpath "$1") crowdprof=$(realpath "$2")
work=$(dirname "$crowdprof")/ab-gate-test
gate=$source_dir/tests/ci/ab_gate.sh
scene=$source_dir/scenes/humanoid.glb
fail() { echo "ab_gate_test: $*" >&2; exit 1; }
trap 'echo "ab_gate_test: line $LINENO: \"$BASH_COMMAND\" failed (status $?)" >&2' ERR
rm -rf "$work" && mkdir -p "$work"
small=(-n 12 --frames 6 --warmup 1 --groups 6)

# 1. The same binary twice.
status=0
"$gate" "$crowdprof" "$crowdprof" "$work/same" "$scene" "${small[@]}" --tolerance 1000% >"$work/same.log" 2>&1 || status=$?
((status == 0)) || fail "the same binary twice exited $status: $(cat "$work/same.log")"
grep -q '^work: the same (digest ' "$work/same.log" || fail "no work line: $(cat "$work/same.log")"
python3 - "$work/same" <<'PY'
import json, sys, xml.etree.ElementTree as ET
out = sys.argv[1]
suites = ET.parse(out + "/junit.xml").getroot()
assert suites.tag == "testsuites" and suites.get("failures") == "0", ET.tostring(suites)
cases = [case.get("name") for case in suites.iter("testcase")]
assert cases == ["frame", "work"], cases
assert not list(suites.iter("failure"))
ab = json.load(open(out + "/ab.json"))
assert ab["crowdprof"]["kind"] == "ab_check"
assert ab["builds"]["base"]["version"].startswith("crowdprof ") and ab["builds"]["current"]["version"].startswith("crowdprof ")
assert ab["builds"]["base"]["environment"]["simd"], ab["builds"]["base"]
assert len(ab["processes"]) == 24 and {p["build"] for p in ab["processes"]} == {"base", "current"}
assert [p["build"] for p in ab["processes"][:4]] == ["base", "current", "current", "base"]  # ABBA
assert [p["build"] for p in ab["processes"][4:8]] == ["current", "base", "base", "current"]  # then BAAB
assert ab["work"]["equal"] and ab["work"]["base_digest"] == ab["work"]["current_digest"]
assert ab["metrics"][0]["metric"] == "frame" and len(ab["metrics"][0]["ratios"]) == 6
assert ab["wall_s"] > 0 and not ab["regressed"]
summary = open(out + "/summary.md").read()
assert summary.startswith("### crowdprof check --against (humanoid.glb × 12, threaded): passed"), summary
assert "| frame |" in summary and "Work: the same" in summary, summary
html = open(out + "/report.html").read()
assert "<html" in html and "base" in html and "current" in html
PY

# 2. A base that does other work: twice the copies, in a wrapper.
cat >"$work/more-work" <<WRAPPER
#!/usr/bin/env bash
args=()
while ((\$#)); do
  if [[ \$1 == -n || \$1 == --characters ]]; then args+=("\$1" "\$((\$2 * 2))"); shift 2; else args+=("\$1"); shift; fi
done
exec "$crowdprof" "\${args[@]}"
WRAPPER
chmod +x "$work/more-work"
status=0
"$gate" "$work/more-work" "$crowdprof" "$work/more" "$scene" "${small[@]}" --tolerance 1000% >"$work/more.log" 2>&1 || status=$?
((status == 1)) || fail "other work was not caught (exit $status): $(cat "$work/more.log")"
grep -q '^work: CHANGED' "$work/more.log" || fail "no changed work: $(cat "$work/more.log")"
grep -q "^reproduce: crowdprof check $scene --characters 12 --frames 6 --warmup 1 --tolerance 1000% --groups 6 --against " "$work/more.log" || fail "no reproducing command: $(cat "$work/more.log")"
python3 - "$work/more" <<'PY'
import sys, xml.etree.ElementTree as ET
suites = ET.parse(sys.argv[1] + "/junit.xml").getroot()
failed = [case.get("name") for case in suites.iter("testcase") if case.find("failure") is not None]
assert failed == ["work"], failed
assert "copies" in suites.find(".//failure").get("message") or "digest" in suites.find(".//failure").get("message")
assert open(sys.argv[1] + "/summary.md").read().startswith("### crowdprof check --against (humanoid.glb × 12, threaded): FAILED")
PY

# 3. Bad base builds: one line naming the binary, exit 3, before anything runs.
printf '#!/bin/sh\necho hello\n' >"$work/not-crowdprof" && chmod +x "$work/not-crowdprof"
printf 'not a program\n' >"$work/not-executable"
cat >"$work/bad-results" <<WRAPPER
#!/usr/bin/env bash
[[ \$1 == --version ]] && exec "$crowdprof" --version
out=
while ((\$#)); do [[ \$1 == --json ]] && out=\$2; shift; done
echo '{"crowdprof": {"format": 1}}' >"\$out"
WRAPPER
chmod +x "$work/bad-results"
for base in "$work/missing" "$work/not-executable" "$work/not-crowdprof" "$work/bad-results"; do
  status=0
  "$crowdprof" check "$scene" "${small[@]}" --against "$base" --junit "$work/bad.xml" >"$work/bad.out" 2>"$work/bad.err" || status=$?
  ((status == 3)) || fail "base $base: exit $status, not 3: $(cat "$work/bad.err")"
  (($(wc -l <"$work/bad.err") == 1)) || fail "base $base: not one line: $(cat "$work/bad.err")"
  grep -q "^crowdprof: $base: " "$work/bad.err" || fail "base $base: not named: $(cat "$work/bad.err")"
  [[ ! -e $work/bad.xml && ! -s $work/bad.out ]] || fail "base $base: something was written"
done
# Options that belong to a stored baseline.
status=0
"$crowdprof" check "$scene" --against "$crowdprof" --baseline "$work/x.json" 2>"$work/usage.err" || status=$?
((status == 2)) && grep -q -- "--baseline is not for an A/B" "$work/usage.err" || fail "--baseline with --against: $(cat "$work/usage.err")"

# 4. A stored baseline's verdict in the same formats.
"$crowdprof" check "$scene" -n 12 --frames 6 --warmup 1 --runs 2 --baseline "$work/base.json" --update-baseline -q
status=0
"$crowdprof" check --baseline "$work/base.json" --runs 2 --tolerance 1000% --metric frame,Animations \
  --junit "$work/stored.xml" --markdown "$work/stored.md" >"$work/stored.log" 2>&1 || status=$?
((status == 0)) || fail "the stored check exited $status: $(cat "$work/stored.log")"
python3 - "$work" <<'PY'
import sys, xml.etree.ElementTree as ET
suites = ET.parse(sys.argv[1] + "/stored.xml").getroot()
assert [case.get("name") for case in suites.iter("testcase")] == ["frame", "Animations", "work"]
assert suites.get("failures") == "0"
assert open(sys.argv[1] + "/stored.md").read().startswith("### crowdprof check (humanoid.glb × 12, threaded): passed")
PY

# 5. The documented workflow parses, and calls this script as tested here.
python3 - "$source_dir/docs/ci.md" <<'PY'
import re, sys, yaml
text = open(sys.argv[1]).read()
blocks = re.findall(r"```yaml\n(.*?)```", text, re.S)
assert len(blocks) == 1, "docs/ci.md holds one workflow"
workflow = yaml.safe_load(blocks[0])
steps = [step for job in workflow["jobs"].values() for step in job["steps"]]
runs = [step.get("run", "") for step in steps]
calls = [run for run in runs if "tests/ci/ab_gate.sh" in run]
assert calls == ["tests/ci/ab_gate.sh ../base/build/crowdprof build/crowdprof ab-check scenes/thesis.json\n"], calls
assert any(step.get("with", {}).get("path") == "ab-check/" for step in steps), "the report and JUnit are kept"
script = re.findall(r"```sh\n(.*?)```", text, re.S)
assert any("tests/ci/ab_gate.sh ../base/build/crowdprof build/crowdprof ab-check scenes/thesis.json" in s for s in script)
PY
rm -rf "$work"
echo "ab_gate_test: same binary passed, other work caught, 4 bad bases refused, workflow checked"
