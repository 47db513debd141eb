#!/bin/sh
# cross-test.sh ARCH HOST_BUILD - issue 17 item 6, run by `make test-cross`: swell for ARCH
# (arm64) with Debian's cross toolchain and multiarch libraries (the Makefile's CC, PKG_CONFIG
# and binutils), its C unit tests run under qemu-user, and one surfaceless frame rendered by
# the ARCH build (llvmpipe's code for ARCH, emulated) compared with the same frame from
# HOST_BUILD: same tables, same view, at most 4/255 per channel and RMSE 1.0 (measured on
# arm64: 2/255, RMSE 0.38; llvmpipe's arm64 code rounds differently, never more).
# armhf: Debian's armhf security index was unreadable on this project's mirror (apt-get update
# "File has unexpected size"), so armhf packages could not match the amd64 ones installed;
# the script builds for armhf where they can be installed.
set -eu
arch=${1:-arm64}
host=${2:-build/rel}
case $arch in
    arm64) triplet=aarch64-linux-gnu; qemu=qemu-aarch64 ;;
    armhf) triplet=arm-linux-gnueabihf; qemu=qemu-arm ;;
    *) echo "cross-test.sh: ARCH is arm64 or armhf, not '$arch'" >&2; exit 2 ;;
esac
tools/install-deps.sh --cross "$arch"
build=build/$arch
make -j2 --no-print-directory BUILD="$build" CC="$triplet-gcc" PKG_CONFIG="$triplet-pkg-config" \
    SWELL_EXEC="$qemu" test-unit-exec
# one frame: the host bakes, both render it
tmp=$build/tmp/cross-frame
rm -rf "$tmp"; mkdir -p "$tmp"
"$host/swell-bake" --size 16 --size-geo 8 --frames 4 --patterns 2 --quiet --out "$tmp/tables"
view="--platform surfaceless --tables $tmp/tables --size 64x64 --frames 1 --time 3.7"
# shellcheck disable=SC2086
"$host/swell" $view --out "$tmp/host.png" >/dev/null
# shellcheck disable=SC2086
"$qemu" "$build/swell" $view --out "$tmp/$arch.png" >/dev/null
"$host/tools/image-diff" "$tmp/$arch.png" "$tmp/host.png" 4 1.0
echo "cross-test: $arch unit tests and a frame against the host's passed"
