#!/bin/sh
# init.sh - /init of the KMS test VM (busybox). Loads virtio/9p/overlay/vkms, mounts the host's
# root read-only over virtio-9p under a tmpfs overlay, mounts the writable result share at the
# same absolute path the host uses, runs $swell_share/cmd in a chroot with cwd $swell_cwd, writes
# its exit status to the share and powers off. swell_share, swell_cwd and swell_vkms (module
# parameters for vkms) come from the kernel command line (key=value words become init's env).
# shellcheck disable=SC2154  # swell_share, swell_cwd come from the kernel command line
/bin/busybox --install -s /bin
export PATH=/bin

fail() { echo "kms vm init: $*"; poweroff -f; }

mount -t proc proc /proc
mount -t sysfs sysfs /sys
mount -t devtmpfs devtmpfs /dev
for m in $(cat /lib/modules/order); do
    args=""
    [ "$m" = vkms.ko ] && args=$(echo "${swell_vkms:-}" | tr ',' ' ')
    # shellcheck disable=SC2086
    insmod "/lib/modules/$m" $args || fail "insmod $m failed"
done

o9p=trans=virtio,version=9p2000.L,msize=512000
mount -t 9p -o "$o9p,cache=loose,ro" hostroot /host || fail "cannot mount the host root (9p)"
mount -t tmpfs -o size=512m tmpfs /upper
mkdir -p /upper/u /upper/w
mount -t overlay overlay -o lowerdir=/host,upperdir=/upper/u,workdir=/upper/w /newroot ||
    fail "cannot mount the overlay root"
mount -t 9p -o "$o9p" share /share || fail "cannot mount the result share (9p)"

R=/newroot
mount -t proc proc $R/proc
mount -t sysfs sysfs $R/sys
mount -t devtmpfs devtmpfs $R/dev
mkdir -p $R/dev/pts $R/dev/shm
mount -t devpts devpts $R/dev/pts
mount -t tmpfs tmpfs $R/dev/shm
mount -t debugfs debugfs $R/sys/kernel/debug 2>/dev/null
mount -t tmpfs tmpfs $R/run
mkdir -p "$R$swell_share"
mount --bind /share "$R$swell_share" || fail "cannot bind the share at $swell_share"

chroot $R /bin/sh -c 'cd "$1" && exec /bin/sh "$2/cmd"' sh "$swell_cwd" "$swell_share" \
    > /share/out.log 2>&1
echo $? > /share/status
sync
umount "$R$swell_share" 2>/dev/null
umount /share
poweroff -f
