#!/usr/bin/env bash
# README's Quick start and Install as a new user meets them, in a fresh build
# folder: Quick start's first command (./setup.sh run); then README's Install
# lines, read from README and run as written, from a folder whose build/ is
# that fresh one (DESTDIR keeps cmake --install out of the system; cpack
# writes into build/); then, with the installed binary, every shipped scene
# and every example of every --help, from an empty folder outside the source
# and build trees (nothing of either at hand, as from /); the guides --help
# names, installed and in the .deb; and every scene file the source tree holds
# or the docs name, from the checkout, as the docs run them.
#   quick_start_test.sh SOURCE_DIR BUILD_DIR
set -Eeuo pipefail
source_dir=$(realpath "$1") build_dir=$(realpath "$2")
work=$build_dir/quick-start-test
fail() { echo "quick_start_test: $*" >&2; exit 1; }
trap 'echo "quick_start_test: line $LINENO: \"$BASH_COMMAND\" failed (status $?)" >&2' ERR
rm -rf "$work" && mkdir -p "$work/cwd"
fresh=$work/build readme=$source_dir/README.md

# A fenced sh block's lines under a README heading, comments and blank lines dropped.
block() {
  awk -v heading="$1" '$0 == heading {h = 1; next} h && /^## / {exit} h && /^```sh/ {f = 1; next}
    f && /^```/ {exit} f {sub(/[ \t]+#.*$/, ""); if (NF) print}' "$readme"
}

mapfile -t quick < <(block "## Quick start (Debian 12)")
[[ ${quick[0]:-} == "./setup.sh run" ]] || fail "README's Quick start does not begin with ./setup.sh run: '${quick[0]:-}'"
(cd "$source_dir" && CROWDPROF_BUILD_DIR=$fresh bash -c "${quick[0]}") >"$work/run.out" 2>&1 ||
  fail "'${quick[0]}' into a fresh build folder failed: $(tail -5 "$work/run.out")"
grep -q '^Frametime' "$work/run.out" || fail "'${quick[0]}' printed no profile table: $(tail -5 "$work/run.out")"

mapfile -t install < <(block "## Install")
((${#install[@]} >= 2)) || fail "README's Install block has ${#install[@]} lines"
ln -s "$fresh" "$work/cwd/build"
root=$work/root
for line in "${install[@]}"; do
  (cd "$work/cwd" && DESTDIR=$root bash -c "$line") >>"$work/install.out" 2>&1 ||
    fail "README's Install line '$line' failed right after the Quick start: $(tail -5 "$work/install.out")"
done
prefix=$(find "$root" -path '*/bin/crowdprof' -printf '%h\n' | head -1)/..
[[ -x $prefix/bin/crowdprof ]] || fail "cmake --install installed no bin/crowdprof under $root"
prefix=$(realpath "$prefix")
deb=$(echo "$fresh"/crowdprof_*.deb)
[[ -f $deb ]] || fail "cpack made no crowdprof .deb in build/"
for file in share/crowdprof/scenes/thesis.json share/crowdprof/scenes/mixed.json share/crowdprof/scenes/humanoid.glb \
    share/man/man1/crowdprof-bench.1 share/doc/crowdprof/README.md; do
  [[ -f $prefix/$file ]] || fail "README's Install lines did not install $file"
done

crowdprof=$prefix/bin/crowdprof
listing=$(dpkg-deb -c "$deb")
commands=(info gen bench compare capacity check diff render report)
help=$("$crowdprof" --help)
for command in "${commands[@]}"; do help+=$'\n'$("$crowdprof" "$command" --help); done
for guide in $(grep -o 'docs/[a-z0-9_-]*\.md' <<<"$help" | sort -u); do
  [[ -f $prefix/share/doc/crowdprof/$guide ]] || fail "--help names $guide, which is not installed"
  grep -q " ./usr/share/doc/crowdprof/$guide\$" <<<"$listing" || fail "--help names $guide, which $(basename "$deb") lacks"
done

# From an empty folder outside both trees.
away=$(mktemp -d /tmp/crowdprof-quick-start.XXXXXX)
trap 'rm -rf "$away"' EXIT
mkdir -p "$away/here" "$away/base-build"
for scene in "$prefix"/share/crowdprof/scenes/*.json; do
  out=$(cd "$away/here" && "$crowdprof" bench "$scene" --frames 2 --warmup 0 2>&1) || fail "the shipped $scene: $out"
  grep -q '^Frametime' <<<"$out" || fail "the shipped $scene printed no table: $out"
done
# What the examples take as given, as a user would have it: two results to
# diff, and a base build for the A/B.
(cd "$away/here" && "$crowdprof" bench "$prefix/share/crowdprof/scenes/thesis.json" --frames 20 -q --json before.json &&
  "$crowdprof" bench "$prefix/share/crowdprof/scenes/thesis.json" --frames 20 -q --json after.json) ||
  fail "could not make the diff example's inputs"
ln -s "$crowdprof" "$away/base-build/crowdprof"
ran=0
for command in "" "${commands[@]}"; do
  # shellcheck disable=SC2086 # the top level's help is "crowdprof --help"
  while read -r example; do
    [[ -n $example ]] || continue
    status=0
    (cd "$away/here" && PATH=$prefix/bin:$PATH bash -c "$example") >"$work/example.out" 2>&1 || status=$?
    # check's examples give a verdict either way (1: slower); any other failure is the example's.
    if ((status != 0)) && ! [[ $example == "crowdprof check "* && $status == 1 ]]; then
      fail "the example '$example' failed from an empty folder (exit $status): $(tail -3 "$work/example.out")"
    fi
    ran=$((ran + 1))
  done < <("$crowdprof" $command --help | awk '/^Examples:/ {e = 1; next} e && /^  crowdprof / {sub(/^  /, ""); print}')
done
((ran >= ${#commands[@]} + 1)) || fail "only $ran examples found in --help"

# Every scene file of the source tree, and every one the docs name, from the checkout.
for scene in $( (cd "$source_dir" && ls scenes/*.json; grep -ohE 'crowdprof [a-z]+ [^ `]*scenes/[A-Za-z0-9_-]+\.json' README.md docs/*.md |
  awk '{print $3}') | sort -u); do
  [[ $scene == build/* ]] && fail "the docs run $scene from a build folder, which the Quick start may not have made"
  out=$(cd "$source_dir" && "$fresh/crowdprof" bench "$scene" --frames 2 --warmup 0 2>&1) ||
    fail "$scene, as the docs run it from the checkout: $out"
done
rm -rf "$work"
echo "quick_start_test: Quick start, README's ${#install[@]} Install lines, $ran --help examples from an empty folder, the shipped scenes and the docs' scene files ran"
