#!/bin/sh
# install-deps.sh - install the Debian 12 packages swell needs, if any are missing.
# As root it runs apt-get; otherwise it prints the exact command to run. Idempotent and quick
# when everything is present. Usage: tools/install-deps.sh [--kms]  (--kms adds the VM test kit)
set -eu

# package: what swell uses it for (README "Dependencies" lists the same)
PKGS="build-essential pkg-config
libfftw3-dev
libcmocka-dev
libpng-dev
zlib1g-dev
libcglm-dev
libegl-dev libgles-dev libegl-mesa0 libgl1-mesa-dri libgbm-dev
libdrm-dev libinput-dev libudev-dev
glslang-tools
valgrind
clang libclang-rt-14-dev
jq gnuplot-nox"
KMS_PKGS="qemu-system-x86 busybox-static linux-image-amd64 kmod xz-utils cpio"

want="$PKGS"
[ "${1:-}" = "--kms" ] && want="$PKGS $KMS_PKGS"

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
