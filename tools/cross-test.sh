#!/bin/sh
# cross-test.sh ARCH HOST_BUILD - issue 17 item 6, run by `make test-cross` (CI: arm64 and
# armhf): swell for ARCH built with Debian's cross compiler against a sysroot of Debian's ARCH
# libraries (tools/cross-sysroot.sh; the host's dpkg is not touched), its C unit tests run
# under qemu-user, and frames rendered by the ARCH build compared with the same frames from
# HOST_BUILD (same tables, same view):
#   - softpipe, Mesa's reference rasteriser (no JIT): bit-identical, so swell's own code gives
#     the same picture on ARCH (measured: arm64 and armhf both 0/255);
#   - llvmpipe, what runs on a board without a GPU driver: on arm64 at most 4/255 per channel
#     and RMSE 1.0 (measured 2/255, RMSE 0.38: llvmpipe's arm64 code rounds differently). On
#     armhf llvmpipe under qemu-arm draws another picture (an orange sky, a grey sea: 172/255,
#     RMSE 57-63 on every tier) where softpipe on the same build is bit-identical to x86-64's,
#     so the fault is in llvmpipe's 32-bit ARM code or qemu's emulation of it, not in swell;
#     the armhf llvmpipe frame is rendered (it must not crash) and its difference printed;
#   - on arm64 the five golden scenes (tests/frame/test_golden.c, its tolerance for other CPUs).
set -eu
arch=${1:-arm64}
host=${2:-build/rel}
case $arch in
    arm64) triplet=aarch64-linux-gnu; qemu=qemu-aarch64 ;;
    armhf) triplet=arm-linux-gnueabihf; qemu=qemu-arm ;;
    *) echo "cross-test.sh: ARCH is arm64 or armhf, not '$arch'" >&2; exit 2 ;;
esac
tools/install-deps.sh --cross "$arch"
root=$(tools/cross-sysroot.sh "$arch")
build=build/$arch
mkdir -p "$build"
# pkg-config for the sysroot: its .pc files, paths prefixed with it
pc=$build/pkg-config
cat > "$pc" <<EOF
#!/bin/sh
PKG_CONFIG_SYSROOT_DIR='$root' PKG_CONFIG_LIBDIR='$root/usr/lib/$triplet/pkgconfig:$root/usr/share/pkgconfig' exec pkg-config "\$@"
EOF
chmod +x "$pc"
# qemu-user takes the ARCH programs' loader, libraries and Mesa's drivers from the sysroot
export QEMU_LD_PREFIX="$root"
make -j2 --no-print-directory BUILD="$build" CC="$triplet-gcc --sysroot=$root" PKG_CONFIG="$pc" \
    SWELL_EXEC="$qemu" test-unit-exec
# the frames: the host bakes, both render
tmp=$build/tmp/cross-frame
rm -rf "$tmp"; mkdir -p "$tmp"
"$host/swell-bake" --size 16 --size-geo 8 --frames 4 --patterns 2 --quiet --out "$tmp/tables"
view="--platform surfaceless --tables $tmp/tables --size 64x64 --frames 1 --time 3.7"
# shellcheck disable=SC2086
GALLIUM_DRIVER=softpipe "$host/swell" $view --out "$tmp/host-softpipe.png" >/dev/null
# shellcheck disable=SC2086
GALLIUM_DRIVER=softpipe "$qemu" "$build/swell" $view --out "$tmp/$arch-softpipe.png" >/dev/null
"$host/tools/image-diff" "$tmp/$arch-softpipe.png" "$tmp/host-softpipe.png" 0 0.0
# shellcheck disable=SC2086
"$host/swell" $view --out "$tmp/host.png" >/dev/null
# shellcheck disable=SC2086
"$qemu" "$build/swell" $view --out "$tmp/$arch.png" >/dev/null
if [ "$arch" = arm64 ]; then
    "$host/tools/image-diff" "$tmp/$arch.png" "$tmp/host.png" 4 1.0
    # the goldens hold across architectures: test_golden's five scenes drawn by the arm64
    # build, its tables baked by it, within the tolerance stated there for other CPUs
    SWELL_BUILD="$build" SWELL_EXEC="$qemu" SWELL_TARGET_ARCH="$arch" SWELL_TMP="$tmp" \
        "$host/tests/test_golden"
else
    echo "cross-test: armhf llvmpipe under qemu-arm (not compared, see the top):"
    "$host/tools/image-diff" "$tmp/$arch.png" "$tmp/host.png" 4 1.0 || true
fi
echo "cross-test: $arch unit tests and frames against the host's passed"
