#!/bin/sh
# run-vm.sh - run one shell command inside the vkms test VM and return its exit status.
#
# Usage: tests/kms/run-vm.sh [-t SECONDS] [-p VKMS_PARAMS] [-k] CACHE_DIR SHARE_DIR 'command'
#   CACHE_DIR  from tests/kms/setup.sh (vmlinux, initramfs.cpio.gz)
#   SHARE_DIR  a host directory, writable in the guest at the same absolute path; the command's
#              output lands in SHARE_DIR/out.log (also printed here), its status in SHARE_DIR/status
#   -t         wall-clock limit for the whole VM (default 240 s)
#   -p         vkms module parameters, comma separated (e.g. enable_writeback=1)
#   -k         kernel console to the terminal (debugging a boot); default quiet
#   -a ACCEL   QEMU accelerator: tcg (default) or kvm (only where a kvm boot was seen to work)
#   -b SECONDS the command keeps SHARE_DIR/heartbeat fresh: once the file exists, the VM is
#              stopped when it was not rewritten for SECONDS (the guest stopped), exit 123
# Env: KMS_QEMU_CPU  guest CPU model under TCG (default Nehalem: SSE4.2, no AVX. llvmpipe's
#      128-bit code runs about twice as fast under TCG as the AVX2 code it emits for -cpu max;
#      measured on swell's frames here)
# The guest sees the host's / read-only with a tmpfs overlay, the current directory as its cwd,
# and the environment variables listed in SHARE_DIR/env (written here: CI, SWELL_*, MESA_*).
# Exit status: the command's; 123 when the heartbeat went stale; 124 on timeout; 125 when the
# VM did not run the command.
set -eu

TIMEOUT=240
VKMS=""
CONSOLE=quiet
ACCEL=tcg
BEAT=0
while getopts t:p:ka:b: o; do
    case $o in
        t) TIMEOUT=$OPTARG ;;
        p) VKMS=$OPTARG ;;
        k) CONSOLE="" ;;
        a) ACCEL=$OPTARG ;;
        b) BEAT=$OPTARG ;;
        *) exit 125 ;;
    esac
done
shift $((OPTIND - 1))
[ $# -eq 3 ] || { echo "usage: $0 [-t S] [-p P] [-k] CACHE_DIR SHARE_DIR 'command'" >&2; exit 125; }
CACHE=$(cd "$1" && pwd)
mkdir -p "$2"
SHARE=$(cd "$2" && pwd)
CMD=$3
CWD=$(pwd)
case "$SHARE$CWD" in *[[:space:]]*) echo "run-vm: paths with spaces are not supported" >&2; exit 125 ;; esac
command -v qemu-system-x86_64 >/dev/null || { echo "run-vm: qemu-system-x86_64 missing (qemu-system-x86)" >&2; exit 125; }

rm -f "$SHARE/status" "$SHARE/out.log" "$SHARE/heartbeat"
{
    echo "export PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin"
    echo "export HOME=/tmp LANG=C.UTF-8 MESA_LOADER_DRIVER_OVERRIDE=kms_swrast"
    env | grep -E '^(CI|SWELL_[A-Z0-9_]*|MESA_[A-Z0-9_]*|LIBGL_[A-Z0-9_]*|GALLIVM_[A-Z0-9_]*|LP_[A-Z0-9_]*)=' |
        grep -v "'" | sed "s/^\([^=]*\)=\(.*\)$/export \1='\2'/" || true
} > "$SHARE/env"
printf '. "%s/env"\n%s\n' "$SHARE" "$CMD" > "$SHARE/cmd"

# TCG by default: /dev/kvm on some hosts is a paravirtual variant that does not boot a stock
# kernel (notes/kms-vm.md); run-kms-test.sh tries kvm once and passes -a kvm only if it booted.
if [ "$ACCEL" = kvm ]; then
    ACCEL_ARGS="-accel kvm -cpu host"
else
    ACCEL_ARGS="-accel tcg,thread=multi -cpu ${KMS_QEMU_CPU:-Nehalem}"
fi
set +e
# shellcheck disable=SC2086
timeout -k 5 "$TIMEOUT" qemu-system-x86_64 \
    -nodefaults -no-user-config -no-reboot -display none \
    $ACCEL_ARGS -m 1G -smp 2 \
    -kernel "$CACHE/vmlinux" -initrd "$CACHE/initramfs.cpio.gz" \
    -append "console=ttyS0 $CONSOLE panic=-1 cryptomgr.notests mitigations=off swell_share=$SHARE swell_cwd=$CWD swell_vkms=$VKMS" \
    -serial stdio -monitor none \
    -virtfs local,path=/,mount_tag=hostroot,security_model=none,readonly=on,multidevs=remap \
    -virtfs local,path="$SHARE",mount_tag=share,security_model=none \
    < /dev/null > "$SHARE/console.log" 2>&1 &
vm=$!
stale=0
if [ "$BEAT" -gt 0 ]; then
    while kill -0 "$vm" 2>/dev/null; do
        sleep 2
        [ -f "$SHARE/heartbeat" ] || continue
        age=$(($(date +%s) - $(stat -c %Y "$SHARE/heartbeat" 2>/dev/null || date +%s)))
        if [ "$age" -gt "$BEAT" ]; then
            stale=$age
            pkill -TERM -P "$vm" 2>/dev/null
            sleep 5
            pkill -KILL -P "$vm" 2>/dev/null
            break
        fi
    done
fi
wait "$vm"
qrc=$?
set -e
[ -f "$SHARE/out.log" ] && cat "$SHARE/out.log"
if [ "$stale" -gt 0 ]; then
    echo "run-vm: the guest stopped: its heartbeat ($(cat "$SHARE/heartbeat" 2>/dev/null)) was" \
         "not renewed for $stale s; VM stopped. Console's last lines:" >&2
    tail -n 20 "$SHARE/console.log" >&2
    exit 123
fi
if [ "$qrc" -eq 124 ]; then
    echo "run-vm: the VM did not finish within $TIMEOUT s (console: $SHARE/console.log); its" \
         "last lines:" >&2
    tail -n 20 "$SHARE/console.log" >&2
    exit 124
fi
if [ ! -f "$SHARE/status" ]; then
    echo "run-vm: the VM did not run the command (qemu status $qrc); console log follows:" >&2
    tail -n 40 "$SHARE/console.log" >&2
    exit 125
fi
exit "$(cat "$SHARE/status")"
