#!/usr/bin/env bash
# Builds oneTBB with ThreadSanitizer from Debian's source package of the
# installed libtbb-dev (same version, Debian's patches applied) into DIR/onetbb
# and installs it to DIR/onetbb-install; prints nothing else on success. Only
# the tbb library itself is built: no tbbmalloc, no tests, no examples.
# The sources come through apt with a private state in DIR/apt (deb-src lines
# for the system's Debian release), so the system's sources.list stays as is.
# Done once: a second call finds the installed library and returns.
set -euo pipefail
dir=$1
install=$dir/onetbb-install
[[ -f $install/lib/cmake/TBB/TBBConfig.cmake ]] && exit 0

package=$(dpkg-query -W -f='${source:Package}' libtbb-dev)
version=$(dpkg-query -W -f='${source:Version}' libtbb-dev)
codename=$(. /etc/os-release && echo "$VERSION_CODENAME")
apt_dir=$dir/apt
mkdir -p "$apt_dir/lists/partial" "$apt_dir/cache/archives/partial" "$dir/onetbb-src"
cat >"$apt_dir/sources.list" <<LIST
deb-src http://deb.debian.org/debian $codename main
deb-src http://deb.debian.org/debian $codename-updates main
deb-src http://deb.debian.org/debian-security $codename-security main
LIST
apt_options=(-o Dir::Etc::SourceList="$apt_dir/sources.list" -o Dir::Etc::SourceParts=/nonexistent
  -o Dir::State::Lists="$apt_dir/lists" -o Dir::Cache="$apt_dir/cache" -o APT::Sandbox::User=root)
apt-get -qq "${apt_options[@]}" update
(cd "$dir/onetbb-src" && apt-get -qq "${apt_options[@]}" source "$package=$version" >/dev/null)
source_dir=$(find "$dir/onetbb-src" -mindepth 1 -maxdepth 1 -type d | head -1)

CC=clang CXX=clang++ cmake -S "$source_dir" -B "$dir/onetbb-build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_CXX_FLAGS_RELEASE="-O1 -gline-tables-only" \
  -DTBB_SANITIZE=thread -DTBB_TEST=OFF -DTBB_EXAMPLES=OFF -DTBBMALLOC_BUILD=OFF -DTBB_STRICT=OFF \
  -DTBB_DISABLE_HWLOC_AUTOMATIC_SEARCH=ON -DTBB_ENABLE_IPO=OFF -DCMAKE_INSTALL_PREFIX="$install" >/dev/null
cmake --build "$dir/onetbb-build" -j"$(nproc)" >/dev/null
cmake --install "$dir/onetbb-build" >/dev/null
