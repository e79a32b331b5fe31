#!/usr/bin/env bash
# The .deb packages (CPack, cmake/install.cmake), made into the build tree.
#   deb_test.sh BUILD_DIR contents   the packages hold what they should; every
#       shared library the binary needs comes from a package its Depends names;
#       unpacked with dpkg -x, the binary benches the packaged scene from /.
#   deb_test.sh BUILD_DIR chroot     as a user installs it: a clean Debian 12
#       (debootstrap, kept in the build tree for the next run), apt-get install
#       ./crowdprof_*.deb, crowdprof bench from /, an upgrade to a later version,
#       then purge leaves nothing. Needs root and Debian's mirror: skipped (77)
#       without them.
set -Eeuo pipefail
build_dir=$(realpath "$1") stage=$2
work=$build_dir/deb-test
fail() { echo "deb_test: $*" >&2; exit 1; }
# A command that fails under set -e says where, not just the exit status.
trap 'echo "deb_test: line $LINENO: \"$BASH_COMMAND\" failed (status $?)" >&2' ERR
mkdir -p "$work"
# debootstrap mounts /proc and /sys in its root; a run killed midway (ctest's
# timeout) leaves them mounted: undo that before and after.
unmount_work() {
  local mount_point
  for mount_point in $(findmnt -rn -o TARGET | { grep -F "$work/" || true; } | sort -r); do umount -l "$mount_point"; done
}
unmount_work
trap unmount_work EXIT

make_packages() {
  rm -rf "$work/out"
  cpack --config "$build_dir/CPackConfig.cmake" -B "$work/out" >"$work/cpack.log" 2>&1 ||
    { cat "$work/cpack.log" >&2; fail "cpack failed"; }
  deb=$(echo "$work"/out/crowdprof_*.deb)
  dev=$(echo "$work"/out/crowdprof-dev_*.deb)
  [[ -f $deb && -f $dev ]] || fail "cpack made no crowdprof and crowdprof-dev packages"
}

contents() {
  make_packages
  local listing depends
  listing=$(dpkg-deb -c "$deb")
  for file in ./usr/bin/crowdprof ./usr/share/crowdprof/scenes/thesis.json \
      ./usr/share/crowdprof/scenes/mixed.json ./usr/share/doc/crowdprof/docs/modes.md ./usr/share/man/man1/crowdprof-bench.1; do
    grep -q " $file\$" <<<"$listing" || fail "$deb lacks $file"
  done
  grep -q 'libcrowdprof.a$' <<<"$listing" && fail "the library belongs in crowdprof-dev, not $deb"
  grep -q 'crowdprofConfig.cmake$' <<<"$(dpkg-deb -c "$dev")" || fail "$dev lacks the CMake package config"
  # Depends: the package of each library the binary needs (Debian 12's names, from this system).
  depends=$(dpkg-deb -f "$deb" Depends)
  local needed path package
  for needed in $(objdump -p "$build_dir/crowdprof" | awk '$1 == "NEEDED" {print $2}'); do
    # awk reads to the end: an early exit would kill ldconfig with SIGPIPE
    # when its listing passes the pipe's buffer, and pipefail ends the test.
    path=$(ldconfig -p | awk -v lib="$needed" '$1 == lib && /x86-64/ && !found {print $NF; found = 1}')
    [[ -n $path ]] || fail "cannot find $needed"
    package=$(dpkg -S "$(realpath "$path")" 2>/dev/null || dpkg -S "$path") || fail "no package owns $path"
    package=${package%%:*}
    grep -Fxq "$package" <<<"$(sed 's/ *([^)]*)//g; s/, */\n/g' <<<"$depends")" ||
      fail "Depends ($depends) lacks $package, which has $needed"
  done
  rm -rf "$work/root" && dpkg -x "$deb" "$work/root"
  local out
  out=$(cd / && "$work/root/usr/bin/crowdprof" bench "$work/root/usr/share/crowdprof/scenes/thesis.json" \
    --frames 2 --warmup 0) || fail "the unpacked crowdprof failed"
  grep -q '^Frametime' <<<"$out" || fail "no profile table: $out"
  echo "$(basename "$deb"): $(stat -c %s "$deb") bytes; Depends: $depends"
}

in_root() { chroot "$root" /usr/bin/env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin DEBIAN_FRONTEND=noninteractive "$@"; }

chroot_install() {
  if [[ $(id -u) -ne 0 ]] || ! command -v debootstrap >/dev/null; then
    echo "deb_test: skipped: the chroot needs root and debootstrap" >&2; exit 77
  fi
  getent hosts deb.debian.org >/dev/null || { echo "deb_test: skipped: deb.debian.org unreachable" >&2; exit 77; }
  make_packages
  local base=$work/bookworm-minbase.tar
  if [[ ! -f $base ]]; then
    rm -rf "$work/bootstrap"
    debootstrap --variant=minbase bookworm "$work/bootstrap" http://deb.debian.org/debian >"$work/debootstrap.log" 2>&1 ||
      { tail -20 "$work/debootstrap.log" >&2; fail "debootstrap failed"; }
    tar -C "$work/bootstrap" -cf "$base.tmp" . && mv "$base.tmp" "$base" && rm -rf "$work/bootstrap"
  fi
  root=$work/chroot
  rm -rf "$root" && mkdir -p "$root" && tar -C "$root" -xf "$base"
  cp /etc/resolv.conf "$root/etc/resolv.conf"
  cp "$deb" "$root/tmp/"
  in_root apt-get update -qq
  in_root apt-get install -y -qq --no-install-recommends "/tmp/$(basename "$deb")" >"$work/apt.log" 2>&1 ||
    { tail -20 "$work/apt.log" >&2; fail "apt-get install of $(basename "$deb") failed"; }
  local out
  out=$(in_root sh -c 'cd / && crowdprof bench /usr/share/crowdprof/scenes/thesis.json --frames 3 --warmup 1') ||
    fail "crowdprof bench failed in the clean root"
  grep -q '^Frametime' <<<"$out" || fail "no profile table: $out"
  # An upgrade: the same package as version X+1.
  local unpacked=$work/upgrade version
  rm -rf "$unpacked" && dpkg-deb -R "$deb" "$unpacked"
  version=$(dpkg-deb -f "$deb" Version)
  sed -i "s/^Version: .*/Version: $version+1/" "$unpacked/DEBIAN/control"
  dpkg-deb -b "$unpacked" "$root/tmp/crowdprof_upgrade.deb" >/dev/null
  in_root apt-get install -y -qq /tmp/crowdprof_upgrade.deb >>"$work/apt.log" 2>&1 ||
    { tail -20 "$work/apt.log" >&2; fail "the upgrade failed"; }
  [[ $(in_root dpkg-query -W -f='${Version}' crowdprof) == "$version+1" ]] || fail "the upgrade did not take"
  in_root sh -c 'cd / && crowdprof bench /usr/share/crowdprof/scenes/humanoid.glb -n 4 --frames 2 --warmup 0 -q' ||
    fail "crowdprof failed after the upgrade"
  in_root apt-get purge -y -qq crowdprof >>"$work/apt.log" 2>&1 || fail "apt-get purge failed"
  for path in /usr/bin/crowdprof /usr/share/crowdprof /usr/share/man/man1/crowdprof.1.gz /usr/share/man/man1/crowdprof.1; do
    [[ ! -e $root$path ]] || fail "$path is left after purge"
  done
  rm -rf "$root" "$unpacked"
  echo "installed, ran, upgraded and purged $(basename "$deb") in a clean Debian 12 root"
}

case "$stage" in
  contents) contents ;;
  chroot) chroot_install ;;
  *) fail "unknown stage $stage" ;;
esac
