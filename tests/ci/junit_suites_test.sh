#!/usr/bin/env bash
# Two gates in one pipeline read as two suites (issue 55): a stored-baseline
# check of one scene and an A/B check (--against, this binary twice) of
# another, each writing JUnit and Markdown. Parsed: distinct suite names, each
# naming its scene's file and crowd; a numeric `time` on <testsuites>,
# <testsuite> and every <testcase>; no newline inside any attribute (read from
# the raw text: a parser turns one into a space); Markdown titles that differ
# and name the scenes. Asserts on the formats, never on a timed verdict: a
# shared machine can make a run fifty times slower, so a check may pass or fail
# (exit 0 or 1), and the files are read either way.
set -Eeuo pipefail
source_dir=$(realpath "$1") crowdprof=$(realpath "$2")
work=$(dirname "$crowdprof")/junit-suites-test
fail() { echo "junit_suites_test: $*" >&2; exit 1; }
trap 'echo "junit_suites_test: line $LINENO: \"$BASH_COMMAND\" failed (status $?)" >&2' ERR
rm -rf "$work" && mkdir -p "$work"
small=(--frames 4 --warmup 1)

# Gate 1: humanoid.glb, 12 copies, against a stored baseline.
"$crowdprof" check "$source_dir/scenes/humanoid.glb" -n 12 "${small[@]}" --baseline "$work/base.json" --update-baseline -q
status=0
"$crowdprof" check --baseline "$work/base.json" --tolerance 1000% --confirm 0 \
  --junit "$work/stored.xml" --markdown "$work/stored.md" >"$work/stored.log" 2>&1 || status=$?
((status == 0 || status == 1)) || fail "the stored check exited $status: $(cat "$work/stored.log")"

# Gate 2: locomotion.json, 8 copies, mode culled: an A/B of this build with itself.
status=0
"$crowdprof" check "$source_dir/scenes/locomotion.json" -n 8 --mode culled "${small[@]}" --groups 6 \
  --tolerance 1000% --against "$crowdprof" --junit "$work/ab.xml" --markdown "$work/ab.md" >"$work/ab.log" 2>&1 ||
  status=$?
((status == 0 || status == 1)) || fail "the A/B check exited $status: $(cat "$work/ab.log")"

python3 - "$work" <<'PY'
import re, sys, xml.etree.ElementTree as ET
work = sys.argv[1]

def suite_of(name, scene, crowd):
    raw = open(f"{work}/{name}.xml", encoding="utf-8").read()
    for attribute, value in re.findall(r'([\w:-]+)="([^"]*)"', raw):
        assert "\n" not in value and "\r" not in value, f"{name}.xml: {attribute} holds a newline: {value!r}"
    root = ET.fromstring(raw.encode("utf-8"))
    assert root.tag == "testsuites", root.tag
    suites = root.findall("testsuite")
    assert len(suites) == 1, f"{name}.xml: {len(suites)} suites"
    suite = suites[0]
    for element in [root, suite] + suite.findall("testcase"):
        time = element.get("time")
        assert time is not None, f"{name}.xml: <{element.tag} name={element.get('name')!r}> has no time"
        assert float(time) >= 0, f"{name}.xml: time {time!r}"
    assert float(suite.get("time")) > 0, f"{name}.xml: the check took no time: {suite.get('time')!r}"
    assert scene in suite.get("name") and crowd in suite.get("name"), suite.get("name")
    assert {case.get("classname") for case in suite.findall("testcase")} == {suite.get("name")}
    assert [case.get("name") for case in suite.findall("testcase")][-1] == "work"
    return suite.get("name")

stored = suite_of("stored", "humanoid.glb", "× 12")
ab = suite_of("ab", "locomotion.json", "× 8, culled")
assert stored != ab, stored
assert stored.startswith("crowdprof check (") and ab.startswith("crowdprof check --against ("), (stored, ab)

titles = {}
for name, scene in (("stored", "humanoid.glb × 12"), ("ab", "locomotion.json × 8, culled")):
    title = open(f"{work}/{name}.md", encoding="utf-8").readline().rstrip("\n")
    assert title.startswith("### ") and scene in title, title
    assert title.endswith(": passed") or title.endswith(": FAILED"), title
    titles[name] = title
assert titles["stored"] != titles["ab"], titles
print("suites:", stored, "|", ab)
PY
rm -rf "$work"
echo "junit_suites_test: two gates, two suites named by their scenes, times numeric, attributes one line"
