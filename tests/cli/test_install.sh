#!/bin/bash
# test_install.sh - `make install` and `make uninstall` (issue 16): installed into a staging
# root (DESTDIR), the programs find their shaders and presets beside their bin/ (core/datadir.h),
# not in the source tree or the working directory: the installed swell renders from /, and a
# shader removed from the installed tree is missed by name. Every option of --help is in the
# man page. Uninstall removes every file install put there.
set -u
BUILD=${SWELL_BUILD:-build/rel}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/swell-install.XXXXXX") || exit 1
trap 'rm -rf "$tmp"' EXIT
run() { LD_PRELOAD="${SWELL_SAN_PRELOAD:-}" "$@"; }
fail=0
stage=$tmp/stage; prefix=/usr/local; root=$stage$prefix
# -o all: the programs as built (a sanitizer build is not rebuilt without its flags)
if ! out=$(make -s -o all install BUILD="$BUILD" DESTDIR="$stage" PREFIX="$prefix" 2>&1); then
    echo "FAIL: make install: $out"; exit 1
fi
for f in bin/swell bin/swell-bake share/swell/shaders_gles/ocean.frag \
         share/swell/shaders_gles/common.glsl share/swell/tables/rough.preset \
         share/man/man1/swell.1 share/man/man1/swell-bake.1 share/doc/swell/LICENSE; do
    [ -f "$root/$f" ] || { echo "FAIL: $prefix/$f not installed"; fail=1; }
done

# the search order names the installed tree first (not the source tree)
first=$(run "$root/bin/swell" --help | sed -n '/^Data:/{n;p;q}' | sed 's/^ *//')
[ "$(cd "$first" 2>/dev/null && pwd -P)" = "$(cd "$root/share/swell" && pwd -P)" ] ||
    { echo "FAIL: the installed swell looks first in '$first', not $root/share/swell"; fail=1; }

# renders from / with a preset and a baked table set
png=$tmp/frame.png
if ! out=$(cd / && run "$root/bin/swell" --platform surfaceless --preset calm --size 96x54 \
               --out "$png" 2>&1) || [ ! -s "$png" ]; then
    echo "FAIL: the installed swell did not render from /: $out"; fail=1
fi
if ! out=$(cd / && run "$root/bin/swell-bake" --quiet --preset rough --size 32 --size-geo 16 \
               --frames 4 --out "$tmp/tables" 2>&1); then
    echo "FAIL: the installed swell-bake did not bake from /: $out"; fail=1
fi

# the installed shaders are the ones read: one taken away is missed by its installed path
mv "$root/share/swell/shaders_gles/sky.frag" "$tmp/sky.frag"
out=$(cd / && run "$root/bin/swell" --platform surfaceless --size 96x54 --tables "$tmp/tables" \
          --out "$png" 2>&1); rc=$?
case "$rc:$out" in
    1:*"$root/share/swell/shaders_gles/sky.frag"*) ;;
    *) echo "FAIL: with sky.frag gone, exit $rc and not its installed path: $out"; fail=1 ;;
esac
mv "$tmp/sky.frag" "$root/share/swell/shaders_gles/sky.frag"

# SWELL_DATA_DIR alone, when set
out=$(cd / && SWELL_DATA_DIR=$tmp/nothing run "$root/bin/swell" --preset calm --size 96x54 \
          --out "$png" 2>&1); rc=$?
case "$rc:$out" in
    2:*"SWELL_DATA_DIR=$tmp/nothing holds no tables/"*) ;;
    *) echo "FAIL: a SWELL_DATA_DIR without tables/: exit $rc: $out"; fail=1 ;;
esac

# every option --help names is in the man page
for prog in swell swell-bake; do
    page=$(sed 's/\\//g' "$root/share/man/man1/$prog.1")
    for opt in $(run "$root/bin/$prog" --help | grep -o -- '--[a-z][a-z-]*' | sort -u); do
        case $page in *"$opt"*) ;; *) echo "FAIL: $prog.1 lacks $opt"; fail=1 ;; esac
    done
done

# uninstall leaves no file behind
make -s uninstall BUILD="$BUILD" DESTDIR="$stage" PREFIX="$prefix" >/dev/null 2>&1 ||
    { echo "FAIL: make uninstall"; fail=1; }
left=$(find "$stage" -type f)
[ -z "$left" ] || { echo "FAIL: uninstall left: $left"; fail=1; }
[ ! -e "$root/share/swell" ] || { echo "FAIL: uninstall left $prefix/share/swell"; fail=1; }

[ $fail -eq 0 ] && echo "install: staged, rendered from /, data found beside bin/, uninstalled"
exit $fail
