#!/bin/bash
# test_install.sh - `make install` and `make uninstall` (issue 16): installed into a staging
# root (DESTDIR), the programs find their shaders and presets beside their bin/ (core/datadir.h),
# not in the source tree or the working directory: the installed swell renders from /, and a
# shader removed from the installed tree is missed by name. Every option of --help is in the
# man page. The library: the installed swell.h compiles alone (C99, -pedantic), libswell.so
# and libswell.a make only swell_ names visible, and every examples/*.c builds against the
# installed tree with pkg-config alone (shared and static) and runs to exit 0 offscreen from /,
# its data found beside the library. Uninstall removes every file install put there.
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

# the library: the header alone, the exported names, the examples built with pkg-config only
lib=$root/lib
san=""
nm -D "$lib/libswell.so" 2>/dev/null | grep -q __asan_init && san="-fsanitize=address,undefined"
if ! out=$(cc -std=c99 -pedantic -Wall -Wextra -Werror -fsyntax-only -x c "$root/include/swell.h" 2>&1); then
    echo "FAIL: the installed swell.h does not compile alone as C99: $out"; fail=1
fi
bad=$(nm -D --defined-only "$lib/libswell.so" | awk '$2 ~ /[TDBRVW]/ && $3 !~ /^swell_/ {print $3}')
[ -z "$bad" ] || { echo "FAIL: libswell.so exports names without swell_: $bad"; fail=1; }
n_api=$(nm -D --defined-only "$lib/libswell.so" | awk '$3 ~ /^swell_/' | wc -l)
api=$(grep -c '^SWELL_API' "$root/include/swell.h")
[ "$n_api" -eq "$api" ] || { echo "FAIL: libswell.so exports $n_api swell_ names, swell.h declares $api"; fail=1; }
bad=$(nm -g --defined-only "$lib/libswell.a" | awk 'NF == 3 && $3 !~ /^swell_/ {print $3}')
[ -z "$bad" ] || { echo "FAIL: libswell.a makes global names without swell_: $bad"; fail=1; }
[ "$(readlink "$lib/libswell.so")" = libswell.so.0 ] && [ -e "$lib/libswell.so.0" ] ||
    { echo "FAIL: libswell.so is not a link to the soname libswell.so.0"; fail=1; }
export PKG_CONFIG_PATH=$lib/pkgconfig
pc="pkg-config --define-prefix"
for ex in examples/*.c; do
    name=$(basename "$ex" .c)
    # shellcheck disable=SC2046
    if ! out=$(cc -std=c99 $san "$ex" -o "$tmp/$name" $($pc --cflags --libs swell) -lm 2>&1); then
        echo "FAIL: $ex does not build with pkg-config swell: $out"; fail=1; continue
    fi
    if ! out=$(cd / && LD_LIBRARY_PATH=$lib run "$tmp/$name" 2>&1); then
        echo "FAIL: $ex (shared) did not exit 0 from /: $out"; fail=1
    fi
    # shellcheck disable=SC2046
    if ! out=$(cc -std=c99 $san "$ex" -o "$tmp/$name-static" $($pc --cflags swell) \
               -Wl,-Bstatic -lswell -Wl,-Bdynamic $($pc --static --libs-only-other --libs swell | \
               sed 's/-lswell//') -lm 2>&1); then
        echo "FAIL: $ex does not link statically with pkg-config --static swell: $out"; fail=1
        continue
    fi
    if ! out=$(cd / && run "$tmp/$name-static" 2>&1); then
        echo "FAIL: $ex (static) did not exit 0 from /: $out"; fail=1
    fi
done
# an example's shaders are the installed ones, found beside libswell.so
mv "$root/share/swell/shaders_gles/ocean.frag" "$tmp/ocean.frag"
out=$(cd / && LD_LIBRARY_PATH=$lib run "$tmp/buoy" 2>&1); rc=$?
case "$rc:$out" in
    1:*"$root/share/swell/shaders_gles/ocean.frag"*) ;;
    *) echo "FAIL: buoy without the installed ocean.frag: exit $rc, not its path: $out"; fail=1 ;;
esac
mv "$tmp/ocean.frag" "$root/share/swell/shaders_gles/ocean.frag"

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
