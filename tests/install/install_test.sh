#!/usr/bin/env bash
# cmake --install into a scratch prefix inside the build tree, then as a user
# and an engine would use it: the installed binary benches the installed
# scenes from /, the man pages are there, and tests/install/consumer builds
# against the installed library with find_package(crowdprof).
#   install_test.sh SOURCE_DIR BUILD_DIR
set -euo pipefail
source_dir=$1 build_dir=$2
work=$build_dir/install-test
rm -rf "$work"
prefix=$work/prefix
cmake --install "$build_dir" --prefix "$prefix" >/dev/null

fail() { echo "install_test: $*" >&2; exit 1; }
for file in bin/crowdprof share/crowdprof/scenes/thesis.json share/crowdprof/scenes/mixed.json \
    share/crowdprof/scenes/humanoid.glb share/doc/crowdprof/README.md share/doc/crowdprof/docs/modes.md \
    share/man/man1/crowdprof.1 share/man/man1/crowdprof-bench.1 \
    include/crowdprof/asset/gltf_loader.h include/crowdprof/glad/gl.h lib/libcrowdprof.a \
    lib/cmake/crowdprof/crowdprofConfig.cmake; do
  [[ -f $prefix/$file ]] || fail "cmake --install did not install $file"
done
# A man page for every command the top-level help lists.
commands=$("$prefix/bin/crowdprof" --help | sed -n '/^Subcommands:/,/^$/s/^  \([a-z]*\) .*/\1/p')
grep -qx advise <<<"$commands" || fail "the command list was not read from --help: $commands"
for command in $commands; do
  [[ -f $prefix/share/man/man1/crowdprof-$command.1 ]] || fail "no man page crowdprof-$command.1"
done
# The man page of a command holds that command's options and its example.
# (roff escapes each dash: \-\-mode).
page=$prefix/share/man/man1/crowdprof-bench.1
grep -q '^\\fB\\-\\-mode' "$page" || fail "crowdprof-bench.1 lacks --mode"
grep -q '^crowdprof bench ' <<<"$(grep -A2 '^\.SH EXAMPLES' "$page")" || fail "crowdprof-bench.1 lacks its example"

# From /, nothing of the source or build tree at hand (the shaders are in the binary).
out=$(cd / && "$prefix/bin/crowdprof" bench "$prefix/share/crowdprof/scenes/mixed.json" --frames 2 --warmup 0) ||
  fail "the installed crowdprof could not bench the installed mixed.json"
grep -q '^Frametime' <<<"$out" || fail "no profile table: $out"
grep -q 'gen --bones 300 --vertices 12000 --seed 3 ' <<<"$out" || fail "mixed.json's generated character is missing: $out"

cmake -S "$source_dir/tests/install/consumer" -B "$work/consumer" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
cmake --build "$work/consumer" >/dev/null
out=$("$work/consumer/consumer" "$prefix/share/crowdprof/scenes/humanoid.glb")
grep -q '^69 joints, 4951 vertices, 3 actions$' <<<"$out" || fail "the consumer printed: $out"
echo "$out"
