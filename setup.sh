#!/usr/bin/env bash
# crowdprof set-up on Debian 12: install what is missing, configure, build, then
#   ./setup.sh run [bench options]   run the main job on the bundled default scene
#   ./setup.sh test                  run the whole test suite
#   ./setup.sh build                 only build
#   ./setup.sh bench [options]       the micro-benchmarks (Google Benchmark options)
#   ./setup.sh sanitize              ASan+UBSan and TSan builds, tests and a short fuzz (CI's second stage)
#   ./setup.sh fuzz [SECONDS]        run each fuzz target SECONDS (default 60) on the ASan build
#   ./setup.sh valgrind              memcheck of a short bench and of info on a Draco file
#   ./setup.sh coverage              line coverage of lib/ by the test suite (GCC, gcovr)
#   ./setup.sh docs                  remake the README's figures and docs/report-bench.png (docs/figures.sh)
#   ./setup.sh gpu-bundle DIR        a folder to carry to a GPU machine: the binary, its libraries,
#                                    scenes and run.sh, which measures every GPU mode (docs/gpu.md)
# The build goes to ./build (override with CROWDPROF_BUILD_DIR).
set -euo pipefail
cd "$(dirname "$0")"

action=${1:-run}
shift || true
build_dir=${CROWDPROF_BUILD_DIR:-build}
case "$action" in
  run | test | build | bench | sanitize | fuzz | valgrind | coverage | docs) ;;
  gpu-bundle) [[ $# -eq 1 ]] || { echo "usage: ./setup.sh gpu-bundle DIR" >&2; exit 2; } ;;
  *) echo "usage: ./setup.sh [run|test|build|bench|sanitize|fuzz|valgrind|coverage|docs|gpu-bundle DIR] [options]" >&2; exit 2 ;;
esac

# valgrind is built against too: its callgrind.h lets the frames toggle
# callgrind's counting (check --metric instructions). clang-format: the test
# suite checks the layout (.clang-format, tests/ci/format_test.sh).
packages=(build-essential cmake ninja-build git pkg-config
  libtinygltf-dev nlohmann-json3-dev libglm-dev libdraco-dev libtbb-dev libcli11-dev libgtest-dev
  libegl-dev libegl-mesa0 libgl1-mesa-dri libosmesa6-dev python3-glad libstb-dev libhwy-dev libmeshoptimizer-dev
  libbenchmark-dev help2man valgrind clang-format)
# The sanitizer actions build with clang (libFuzzer and the sanitizer runtimes
# are in libclang-rt); dpkg-dev unpacks oneTBB's source package for TSan.
case "$action" in
  sanitize) packages+=(clang libclang-rt-14-dev dpkg-dev) ;;
  fuzz) packages+=(clang libclang-rt-14-dev) ;;
  # gcovr over lcov: one command reads gcov's data, filters to lib/ and writes
  # the summary, the JSON the per-folder table is made from, and the HTML.
  coverage) packages+=(gcovr) ;;
esac
# The tests load the HTML report in a real browser (tests/browser/) and parse
# docs/ci.md's workflow as YAML and run Google Benchmark's compare.py on
# crowdprof's results (tests/ci/); only the
# actions that run the suite (test, coverage) need it, and it is large.
runs_suite=false
[[ $action == test || $action == coverage ]] && runs_suite=true
$runs_suite && packages+=(chromium python3-yaml libbenchmark-tools python3-scipy)
[[ $action == docs ]] && packages+=(chromium)
# The .deb's test installs it into a clean Debian 12 root (tests/install/).
$runs_suite && packages+=(debootstrap)

missing=()
for package in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
done
if ((${#missing[@]})); then
  sudo=""
  [[ $(id -u) -eq 0 ]] || sudo=sudo
  echo "setup: installing ${missing[*]}" >&2
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get -o DPkg::Lock::Timeout=900 install -y -qq --no-install-recommends \
    "${missing[@]}" >/dev/null
fi

case "$action" in
  sanitize | fuzz | valgrind | coverage) exec tests/sanitizers/"$action".sh "$@" ;;
esac

cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
# run builds the tool and what installs with it (scenes, man pages), so that
# README's Install lines work right after it; the tests, fuzzers and
# micro-benchmarks come with the other actions.
targets=()
[[ $action == run ]] && targets=(--target crowdprof_tool)
[[ $action == docs ]] && targets=(--target crowdprof_cli)
[[ $action == gpu-bundle ]] && targets=(--target crowdprof_cli crowdprof_scenes)
cmake --build "$build_dir" -j"$(nproc)" "${targets[@]}"

case "$action" in
  run) exec "$build_dir/crowdprof" bench scenes/thesis.json "$@" ;;
  test) exec ctest --test-dir "$build_dir" --output-on-failure -j"$(nproc)" "$@" ;;
  build) ;;
  bench) exec "$build_dir/crowdprof_micro" "$@" ;;
  gpu-bundle) exec tests/gpu_bundle/make.sh "$build_dir" "$@" ;;
  docs) exec docs/figures.sh "$build_dir" ;;
esac
