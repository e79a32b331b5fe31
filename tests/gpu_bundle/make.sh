#!/usr/bin/env bash
# Makes a self-contained folder for a GPU machine that has a driver and little
# else (no network, no Debian packages): the binary, the scenes, the shared
# libraries a bare machine may lack (oneTBB, Draco, Highway, glvnd's libEGL),
# and run.sh, which measures every GPU mode there (see docs/gpu.md).
#   make.sh BUILD_DIR DIR     (./setup.sh gpu-bundle DIR builds first, then calls this)
# The folder must not exist yet or be a bundle made earlier: nothing else is
# overwritten. glibc and libstdc++ are not bundled: the target's own are used,
# so it needs glibc 2.36 (Debian 12) or later.
set -euo pipefail
build_dir=$(realpath "${1:?usage: make.sh BUILD_DIR DIR}")
bundle=${2:?usage: make.sh BUILD_DIR DIR}
source_dir=$(cd "$(dirname "$0")/../.." && pwd)
fail() { echo "gpu-bundle: $*" >&2; exit 1; }

binary=$build_dir/crowdprof
[[ -x $binary ]] || fail "$binary is not built"
[[ -f $build_dir/scenes/thesis.json ]] || fail "$build_dir/scenes has no scenes (build the scenes target)"
if [[ -e $bundle ]]; then
  [[ -f $bundle/run.sh && -f $bundle/bin/crowdprof ]] || fail "$bundle exists and is not a bundle: choose a new folder"
  rm -rf "$bundle"
fi
mkdir -p "$bundle/bin" "$bundle/lib" "$bundle/scenes"
cp "$binary" "$bundle/bin/"
cp "$source_dir/tests/gpu_bundle/run.sh" "$bundle/"
cp "$build_dir/scenes/humanoid.glb" "$build_dir/scenes/thesis.json" "$build_dir/scenes/mixed.json" "$bundle/scenes/"

# Every library the binary needs but glibc's and the compiler's own, and the
# ones glvnd's libEGL pulls in (libGLdispatch). Mesa is not bundled: on the
# GPU machine the driver's EGL vendor library is the one to use.
keep_system='^(libc|libm|libstdc\+\+|libgcc_s|libdl|libpthread|librt|ld-linux-x86-64)\.so'
ldd "$binary" | awk '$2 == "=>" && $3 ~ /^\// {print $1, $3}' | while read -r name path; do
  [[ $name =~ $keep_system ]] && continue
  cp -L "$path" "$bundle/lib/$name"
done
[[ -f $bundle/lib/libEGL.so.1 ]] || fail "the binary does not link libEGL: nothing for the GPU to run"
size=$(du -sm "$bundle" | cut -f1)
((size <= 64)) || fail "$bundle is $size MiB, over the 64 MiB a GPU machine's call carries"
echo "gpu-bundle: $bundle ($size MiB): $("$binary" --version)"
echo "gpu-bundle: on the GPU machine: $bundle/run.sh OUT_DIR"
