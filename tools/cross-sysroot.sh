#!/bin/sh
# cross-sysroot.sh ARCH - a sysroot of Debian 12's ARCH libraries swell builds and runs
# against, for a cross build where multiarch cannot install them (issue 17 item 6: armhf).
#
# Why: multiarch packages must be the same version on every architecture, and on this
# project's mirror the armhf index of bookworm-security cannot be read (apt-get update: "File
# has unexpected size"), so the armhf copies of libraries the host has from the security
# archive can never match them. A sysroot needs no match: this script runs a private apt
# (its own lists, cache and an empty dpkg status, the host's sources without the security
# suite, only ARCH), downloads the closure of the libraries' dependencies and unpacks each
# package with dpkg-deb. The host's dpkg and apt are not touched.
#
# Prints the sysroot's path. It is kept in $SWELL_CACHE (default /var/cache/swell) under
# sysroot-ARCH-<hash of the package list>, made again only when that list changes.
set -eu
arch=${1:?usage: tools/cross-sysroot.sh ARCH}
case $arch in
    armhf|arm64) ;;
    *) echo "cross-sysroot.sh: ARCH is armhf or arm64, not '$arch'" >&2; exit 2 ;;
esac
# what swell links (README "Dependencies"), the C library's headers and the unit tests' cmocka
PKGS="libc6-dev libfftw3-dev libpng-dev zlib1g-dev libcglm-dev libegl-dev libgles-dev
libegl-mesa0 libgl1-mesa-dri libgbm-dev libdrm-dev libinput-dev libudev-dev libcmocka-dev"
cache=${SWELL_CACHE:-/var/cache/swell}
key=$(printf '%s %s\n' "$arch" "$PKGS" | md5sum | cut -c1-12)
root=$cache/sysroot-$arch-$key
if [ -f "$root/.complete" ]; then
    echo "$root"
    exit 0
fi
command -v dpkg-deb >/dev/null || { echo "cross-sysroot.sh: dpkg-deb missing" >&2; exit 1; }
[ "$(id -u)" -eq 0 ] || [ -w "$cache" ] 2>/dev/null ||
    { echo "cross-sysroot.sh: cannot write $cache: run as root or set SWELL_CACHE" >&2; exit 1; }
work=$root.work
rm -rf "$work" "$root"
mkdir -p "$work/etc/sources.list.d" "$work/etc/preferences.d" "$work/lists/partial" \
         "$work/archives/partial" "$work/dpkg/updates" "$work/dpkg/info"
: > "$work/dpkg/status"
# the host's sources (deb822 or one-line), the security suite left out
for f in /etc/apt/sources.list /etc/apt/sources.list.d/*.sources /etc/apt/sources.list.d/*.list; do
    [ -f "$f" ] || continue
    case $f in
        *.sources) awk 'BEGIN { RS = ""; ORS = "\n\n" } !/-security/ && /Types:/' "$f" \
                       > "$work/etc/sources.list.d/$(basename "$f")" ;;
        *) grep -v -e '-security' -e '^#' "$f" | grep '^deb ' \
               > "$work/etc/sources.list.d/$(basename "$f").list" || true ;;
    esac
done
apt_p() {
    apt-get -q -o "APT::Architecture=$arch" -o "APT::Architectures=$arch" \
        -o "Dir::Etc::SourceList=/dev/null" -o "Dir::Etc::SourceParts=$work/etc/sources.list.d" \
        -o "Dir::Etc::Preferences=/dev/null" -o "Dir::Etc::PreferencesParts=$work/etc/preferences.d" \
        -o "Dir::State::Lists=$work/lists" -o "Dir::State::status=$work/dpkg/status" \
        -o "Dir::Cache::Archives=$work/archives" -o "Dir::Cache::pkgcache=" \
        -o "Dir::Cache::srcpkgcache=" -o "Debug::NoLocking=1" \
        -o "APT::Sandbox::User=root" "$@"
}
apt_p update >/dev/null
# shellcheck disable=SC2086
apt_p install -y --download-only --no-install-recommends $PKGS >/dev/null
mkdir -p "$work/root"
n=0
for deb in "$work"/archives/*.deb; do
    dpkg-deb -x "$deb" "$work/root"
    n=$((n + 1))
done
# absolute symlinks point into the host; make them relative to the sysroot
find "$work/root" -type l | while read -r l; do
    t=$(readlink "$l")
    case $t in
        /*) ln -sfn "$(realpath -m -s --relative-to="$(dirname "$l")" "$work/root$t")" "$l" ;;
    esac
done
mv "$work/root" "$root"
rm -rf "$work"
echo "$n packages for $arch unpacked $(date -u +%Y-%m-%dT%H:%MZ)" > "$root/.complete"
echo "$root"
