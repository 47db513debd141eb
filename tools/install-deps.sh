#!/bin/sh
# install-deps.sh - install the Debian 12 packages swell needs, if any are missing.
# As root it runs apt-get; otherwise it prints the exact command to run. Idempotent and quick
# when everything is present. Usage: tools/install-deps.sh [--test] [--kms]
#   (none)  what building and running swell need (`make run`, `make install`)
#   --test  adds the test and benchmark tools (`make test`, `make bench`)
#   --kms   adds the KMS VM test kit (`make test-kms`, part of `make test`)
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
for arg in "$@"; do
    case $arg in
        --test) want="$want $TEST_PKGS" ;;
        --kms) want="$want $KMS_PKGS" ;;
        *) echo "usage: tools/install-deps.sh [--test] [--kms]" >&2; exit 2 ;;
    esac
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
