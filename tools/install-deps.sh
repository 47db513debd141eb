#!/bin/sh
# install-deps.sh - install the Debian 12 packages swell needs, if any are missing.
# As root it runs apt-get; otherwise it prints the exact command to run. Idempotent and quick
# when everything is present. Usage: tools/install-deps.sh [--test] [--kms] [--cross ARCH]
#   (none)  what building and running swell need (`make run`, `make install`)
#   --test  adds the test and benchmark tools (`make test`, `make bench`)
#   --kms   adds the KMS VM test kit (`make test-kms`, part of `make test`)
#   --cross ARCH  adds the cross compiler for ARCH (arm64, armhf) and qemu-user (`make
#           test-cross`); ARCH's libraries come as a sysroot (tools/cross-sysroot.sh), so
#           the host's dpkg gains no architecture
set -eu

# package: what swell uses it for (README "Dependencies" lists the same)
PKGS="build-essential pkg-config
libfftw3-dev
libpng-dev
zlib1g-dev
libcglm-dev
libegl-dev libgles-dev libegl-mesa0 libgl1-mesa-dri libgbm-dev
libdrm-dev libinput-dev libudev-dev"
TEST_PKGS="libcmocka-dev
glslang-tools
valgrind
clang libclang-rt-14-dev
jq gnuplot-nox"
KMS_PKGS="qemu-system-x86 busybox-static linux-image-amd64 kmod xz-utils cpio"

want="$PKGS"
cross=""
while [ $# -gt 0 ]; do
    case $1 in
        --test) want="$want $TEST_PKGS" ;;
        --kms)
            # the KMS VM boots Debian's amd64 kernel with a vkms module built for it
            # (tests/kms/setup.sh): an x86-64 host only; make test says what it skips elsewhere
            if [ "$(dpkg --print-architecture)" = amd64 ]; then want="$want $KMS_PKGS"
            else echo "swell: no KMS VM kit on $(dpkg --print-architecture): its VM is x86-64 (make test skips test-kms)"; fi ;;
        --cross)
            cross=${2:-}; shift
            case $cross in
                arm64) want="$want gcc-aarch64-linux-gnu qemu-user" ;;
                armhf) want="$want gcc-arm-linux-gnueabihf qemu-user" ;;
                *) echo "install-deps.sh: --cross arm64|armhf" >&2; exit 2 ;;
            esac ;;
        *) echo "usage: tools/install-deps.sh [--test] [--kms] [--cross ARCH]" >&2; exit 2 ;;
    esac
    shift
done

missing=""
for p in $want; do
    st=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
    case "$st" in
        *"install ok installed"*) ;;
        *) missing="$missing $p" ;;
    esac
done

[ -z "$missing" ] && exit 0

echo "swell: missing Debian packages:$missing"
if [ "$(id -u)" -ne 0 ]; then
    echo "swell: run as root:  apt-get update && apt-get install -y$missing" >&2
    exit 1
fi
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq
# shellcheck disable=SC2086
apt-get install -y -qq --no-install-recommends $missing
echo "swell: installed$missing"
