#!/bin/sh
# setup.sh - build (once) what the KMS test VM boots: an uncompressed Debian kernel, vkms built
# out of tree for that kernel's ABI, and a busybox initramfs carrying the modules.
#
# Debian's kernels do not ship vkms (CONFIG_DRM_VKMS unset), so it is compiled from the matching
# linux-source tarball against linux-headers-$ABI. The ABI is the one linux-image-amd64 depends
# on (the kernel the VM boots, not the host's running kernel). Everything is cached under
# build/kms/$ABI/; a second call only checks the stamp and prints the directory.
#
# Usage: tests/kms/setup.sh [BUILD_ROOT]   (default build/kms)  -> prints the cache directory.
# Needs: linux-image-amd64 busybox-static kmod xz-utils cpio, linux-headers-$ABI, and
# linux-source-$MAJOR.$MINOR (fetched with `apt-get download`, not installed).
set -eu

HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=${1:-build/kms}

die() { echo "kms setup: $*" >&2; exit 1; }
need() { command -v "$1" >/dev/null 2>&1 || die "'$1' not found: install $2 (tools/install-deps.sh --kms)"; }
need apt-cache apt
need modprobe kmod
need cpio cpio
need xz xz-utils
[ -x /bin/busybox ] || die "/bin/busybox missing: install busybox-static"
file_is_static() { ! ldd "$1" >/dev/null 2>&1; }
file_is_static /bin/busybox || die "/bin/busybox is dynamically linked: install busybox-static"

ABI=$(apt-cache depends linux-image-amd64 2>/dev/null |
      sed -n 's/^ *Depends: linux-image-\([0-9].*-amd64\)$/\1/p' | head -n 1)
[ -n "$ABI" ] || die "cannot find the kernel ABI linux-image-amd64 depends on (is it installed?)"
[ -f "/boot/vmlinuz-$ABI" ] || die "/boot/vmlinuz-$ABI missing: apt-get install linux-image-amd64"

OUT="$ROOT/$ABI"
STAMP="$OUT/ready"
mkdir -p "$OUT"
OUT=$(cd "$OUT" && pwd)
# The stamp names the inputs; any change (kernel update, new setup script) rebuilds.
KEY="$ABI $(stat -c %Y "/boot/vmlinuz-$ABI") $(cksum < "$HERE/setup.sh" | cut -d' ' -f1) \
$(cksum < "$HERE/init.sh" | cut -d' ' -f1)"
if [ -f "$STAMP" ] && [ "$(cat "$STAMP")" = "$KEY" ]; then
    echo "$OUT"
    exit 0
fi
rm -f "$STAMP"

MAJMIN=$(echo "$ABI" | sed 's/^\([0-9]*\.[0-9]*\).*/\1/')
HDR="/usr/src/linux-headers-$ABI"
if [ ! -d "$HDR" ]; then
    [ "$(id -u)" -eq 0 ] || die "$HDR missing: run as root: apt-get install linux-headers-$ABI"
    echo "kms setup: installing linux-headers-$ABI" >&2
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "linux-headers-$ABI" >&2
fi

# 1. vmlinux: the xz payload of the bzImage. PVH-booting the ELF is ~3 s faster under TCG.
if [ ! -s "$OUT/vmlinux" ]; then
    off=$(LC_ALL=C grep -abo "$(printf '\3757zXZ')" "/boot/vmlinuz-$ABI" | head -n 1 | cut -d: -f1)
    [ -n "$off" ] || die "no xz payload in /boot/vmlinuz-$ABI"
    # xz stops at the end of its stream and complains about the trailing bzImage bytes.
    tail -c "+$((off + 1))" "/boot/vmlinuz-$ABI" | xz -dcq > "$OUT/vmlinux.tmp" 2>/dev/null || true
    [ "$(head -c 4 "$OUT/vmlinux.tmp" | od -An -c | tr -d ' ')" = '177ELF' ] ||
        die "extracting vmlinux from /boot/vmlinuz-$ABI did not give an ELF file"
    mv "$OUT/vmlinux.tmp" "$OUT/vmlinux"
fi

# 2. vkms.ko from the Debian source of the same kernel series.
if [ ! -s "$OUT/vkms.ko" ]; then
    SRCDEB=$(ls "$OUT"/linux-source-"$MAJMIN"_*.deb 2>/dev/null | head -n 1 || true)
    if [ -z "$SRCDEB" ]; then
        echo "kms setup: downloading linux-source-$MAJMIN" >&2
        (cd "$OUT" && apt-get download "linux-source-$MAJMIN" >&2) ||
            die "apt-get download linux-source-$MAJMIN failed (apt-get update? network?)"
        SRCDEB=$(ls "$OUT"/linux-source-"$MAJMIN"_*.deb | head -n 1)
    fi
    rm -rf "$OUT/vkms-src"
    mkdir -p "$OUT/vkms-src"
    dpkg-deb --fsys-tarfile "$SRCDEB" |
        tar -xOf - "./usr/src/linux-source-$MAJMIN.tar.xz" |
        xz -dc | tar -xf - -C "$OUT/vkms-src" --strip-components=5 \
            "linux-source-$MAJMIN/drivers/gpu/drm/vkms"
    [ -f "$OUT/vkms-src/vkms_drv.c" ] || die "vkms sources not found in $SRCDEB"
    make -s -C "$HDR" M="$OUT/vkms-src" CONFIG_DRM_VKMS=m modules >&2 ||
        die "building vkms against $HDR failed"
    cp "$OUT/vkms-src/vkms.ko" "$OUT/vkms.ko"
    rm -f "$SRCDEB"
fi

# 3. initramfs: busybox as /init's shell, the modules in load order, the init script.
IR="$OUT/initramfs.d"
rm -rf "$IR"
mkdir -p "$IR/bin" "$IR/lib/modules" "$IR/proc" "$IR/sys" "$IR/dev" "$IR/newroot" \
         "$IR/host" "$IR/upper" "$IR/share" "$IR/tmp"
cp /bin/busybox "$IR/bin/busybox"
ln -s busybox "$IR/bin/sh"
: > "$IR/lib/modules/order"
add_mods() {
    modprobe -D -S "$ABI" "$@" | while read -r kind path _; do
        [ "$kind" = insmod ] || continue
        name=$(basename "$path")
        grep -qx "$name" "$IR/lib/modules/order" && continue
        case "$path" in
            *.xz) xz -dc "$path" > "$IR/lib/modules/${name%.xz}"; name=${name%.xz} ;;
            *.zst) zstd -dcq "$path" > "$IR/lib/modules/${name%.zst}"; name=${name%.zst} ;;
            *) cp "$path" "$IR/lib/modules/$name" ;;
        esac
        echo "$name" >> "$IR/lib/modules/order"
    done
}
for m in virtio_pci 9pnet_virtio 9p overlay; do add_mods "$m"; done
# vkms is not in the kernel's module tree: resolve its dependencies by name.
for m in $(modinfo -F depends "$OUT/vkms.ko" | tr ',' ' '); do add_mods "$m"; done
cp "$OUT/vkms.ko" "$IR/lib/modules/vkms.ko"
echo vkms.ko >> "$IR/lib/modules/order"
cp "$HERE/init.sh" "$IR/init"
chmod 755 "$IR/init"
(cd "$IR" && find . | LC_ALL=C sort | cpio -o -H newc --quiet) | gzip -1 > "$OUT/initramfs.cpio.gz"
rm -rf "$IR"

echo "$KEY" > "$STAMP"
echo "$OUT"
