#!/usr/bin/env bash
# ./setup.sh valgrind: valgrind's memcheck over a short bench (the threaded
# mode, so the workers are watched too) and `info` on a Draco file. The build
# (build-valgrind) is for baseline x86-64 (CROWDPROF_NATIVE=OFF): valgrind
# stops with SIGILL on AVX-512 instructions, which -march=native emits on
# machines that have them. Fails on any memcheck error or any byte definitely
# lost. See docs/fuzzing-and-sanitizers.md.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
dir=${CROWDPROF_VALGRIND_DIR:-$root/build-valgrind}
cmake -S "$root" -B "$dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCROWDPROF_NATIVE=OFF -DCROWDPROF_TESTS=OFF >/dev/null
cmake --build "$dir" -j"$(nproc)" --target crowdprof_cli
cli=$dir/crowdprof
mkdir -p "$dir/memcheck"
"$cli" gen -o "$dir/memcheck/small.glb" --bones 24 --vertices 800 >/dev/null
"$cli" gen -o "$dir/memcheck/small_draco.glb" --bones 24 --vertices 800 --draco >/dev/null

memcheck() {
  local name=$1
  shift
  local log=$dir/memcheck/$name.log
  # Exit 99 for an error or a definite leak; still-reachable memory (Mesa's,
  # TBB's thread pool at exit) is reported in the log, not failed on.
  if valgrind --tool=memcheck --error-exitcode=99 --leak-check=full --errors-for-leak-kinds=definite \
      --show-leak-kinds=definite,indirect --track-origins=yes --log-file="$log" "$cli" "$@" >/dev/null; then
    echo "valgrind: $name: $(grep -o 'ERROR SUMMARY: [0-9]* errors' "$log"), $(grep -o 'definitely lost: [0-9,]* bytes' "$log" || echo 'definitely lost: 0 bytes')"
  else
    echo "valgrind: $name FAILED, see $log" >&2
    grep -E "ERROR SUMMARY|definitely lost|Invalid|uninitialised" "$log" | head -10 >&2
    return 1
  fi
}
memcheck bench bench "$dir/memcheck/small.glb" -n 8 --frames 3 --warmup 1 --mode threaded --threads 2 --backend none -q
memcheck info_draco info "$dir/memcheck/small_draco.glb"
