#!/bin/bash
# test_public_api.sh - the programs built on the public API (issue 16 item 2), as an embedding
# application is: swell-bake and swell call, of everything the library defines, only what
# libswell.so exports (swell.h), their own modules (src/app, src/platform: the display, the
# keyboard, the demo boat, the benchmark) and the core helpers the Makefile links them with
# (APP_HELPERS: arguments, numbers, camera matrices, PNG, files, errors, the data directory; no
# ocean in them). Checked on each object's undefined symbols (nm -u) against the names the
# internal archive defines; and the check is shown to fail on an object that calls an internal
# function. The link enforces it for swell too: it links libswell.a, whose other names
# are local.
set -u
BUILD=${SWELL_BUILD:-build/rel}
lib=$BUILD/libswell-internal.a
so=$BUILD/lib/libswell.so
helper_mods=$(sed -n 's/^APP_HELPERS := //p' Makefile)
app_objs=$(ls "$BUILD"/obj/app/*.o "$BUILD"/obj/platform/*.o 2>/dev/null)
tmp=$(mktemp -d "${TMPDIR:-/tmp}/swell-api.XXXXXX") || exit 1
trap 'rm -rf "$tmp"' EXIT
fail=0
for f in "$lib" "$so"; do
    [ -e "$f" ] || { echo "FAIL: $f is missing (make all)"; exit 1; }
done
nm --defined-only "$lib" 2>/dev/null | awk '$2 ~ /^[TDBR]$/ {print $3}' | sort -u >"$tmp/internal"
nm -D --defined-only "$so" | awk '{print $3}' | sort -u >"$tmp/public"
[ -n "$helper_mods" ] || { echo "FAIL: no APP_HELPERS in the Makefile"; exit 1; }
# the helpers: what the core helper modules and the programs' own modules define
for m in $helper_mods; do echo "$BUILD/obj/core/$m.o"; done >"$tmp/helper_objs"
nm --defined-only $(cat "$tmp/helper_objs") $app_objs 2>/dev/null |
    awk '$2 ~ /^[TDBR]$/ {print $3}' | sort -u >"$tmp/helpers"
[ -s "$tmp/internal" ] && [ -s "$tmp/public" ] ||
    { echo "FAIL: no symbols read from $lib or $so"; exit 1; }

# internal_calls OBJ: the library's names OBJ calls that are neither public nor a helper
internal_calls() {
    nm -u "$1" | awk '{print $2}' | sort -u | comm -12 - "$tmp/internal" |
        comm -23 - "$tmp/public" | comm -23 - "$tmp/helpers"
}

for obj in $app_objs; do
    [ -e "$obj" ] || { echo "FAIL: $obj is missing"; exit 1; }
    bad=$(internal_calls "$obj")
    if [ -n "$bad" ]; then
        echo "FAIL: $(basename "$obj") calls the library's internals: $(echo $bad)"; fail=1
    fi
done
[ $fail -eq 0 ] && echo "ok: $(echo $app_objs | wc -w) program objects call only swell.h's functions, the programs' own and the helpers ($helper_mods)"
# at least some public calls, or the objects read were not the programs'
for main in swell_bake swell; do
    n=$(nm -u "$BUILD/obj/app/$main.o" | awk '{print $2}' | sort -u | comm -12 - "$tmp/public" |
        wc -l)
    [ "$n" -ge 5 ] || { echo "FAIL: $main.o calls only $n public functions"; fail=1; }
done
# the helpers hold no ocean: none of them calls into the library's other modules
for h in $(cat "$tmp/helper_objs"); do
    bad=$(internal_calls "$h")
    [ -z "$bad" ] || { echo "FAIL: helper $(basename "$h") calls internals: $(echo $bad)"; fail=1; }
done

# the check can fail: an object calling an internal module's function is caught
cat >"$tmp/probe.c" <<'EOF'
struct seastate;
void seastate_resolve(struct seastate *s);
void probe(struct seastate *s) { seastate_resolve(s); }
EOF
${CC:-cc} -c -o "$tmp/probe.o" "$tmp/probe.c" || { echo "FAIL: cannot compile the probe"; exit 1; }
[ "$(internal_calls "$tmp/probe.o")" = "seastate_resolve" ] ||
    { echo "FAIL: the check missed a call to seastate_resolve"; fail=1; }
exit $fail
