#!/bin/bash
# test_public_api.sh - the programs built on the public API (issue 16 item 2): a program's main
# object may call, of everything the library defines, only what libswell.so exports (swell.h)
# and the command line's own helpers listed below (argument walk, atomic file write), never an
# internal module. Checked on the object's undefined symbols (nm -u) against the names the
# internal archive defines; and the check is shown to fail on an object that calls an internal
# function. swell-bake is on the public API; swell is not yet (issue 16).
set -u
BUILD=${SWELL_BUILD:-build/rel}
lib=$BUILD/libswell-internal.a
so=$BUILD/lib/libswell.so
helpers="args_next fs_write_atomic"
tmp=$(mktemp -d "${TMPDIR:-/tmp}/swell-api.XXXXXX") || exit 1
trap 'rm -rf "$tmp"' EXIT
fail=0
for f in "$lib" "$so"; do
    [ -e "$f" ] || { echo "FAIL: $f is missing (make all)"; exit 1; }
done
nm --defined-only "$lib" 2>/dev/null | awk '$2 ~ /^[TDBR]$/ {print $3}' | sort -u >"$tmp/internal"
nm -D --defined-only "$so" | awk '{print $3}' | sort -u >"$tmp/public"
printf '%s\n' $helpers | sort -u >"$tmp/helpers"
[ -s "$tmp/internal" ] && [ -s "$tmp/public" ] ||
    { echo "FAIL: no symbols read from $lib or $so"; exit 1; }

# internal_calls OBJ: the library's names OBJ calls that are neither public nor a helper
internal_calls() {
    nm -u "$1" | awk '{print $2}' | sort -u | comm -12 - "$tmp/internal" |
        comm -23 - "$tmp/public" | comm -23 - "$tmp/helpers"
}

obj=$BUILD/obj/app/swell_bake.o
[ -e "$obj" ] || { echo "FAIL: $obj is missing"; exit 1; }
bad=$(internal_calls "$obj")
if [ -n "$bad" ]; then
    echo "FAIL: swell-bake calls the library's internals: $(echo $bad)"; fail=1
else
    echo "ok: swell-bake calls only swell.h's functions and its helpers ($(echo $helpers))"
fi
# at least some public calls, or the object read was not the program's
n=$(nm -u "$obj" | awk '{print $2}' | sort -u | comm -12 - "$tmp/public" | wc -l)
[ "$n" -ge 5 ] || { echo "FAIL: swell_bake.o calls only $n public functions"; fail=1; }

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
