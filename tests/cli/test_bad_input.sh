#!/bin/sh
# Bad-input catalogue for both programs (issue 5, "Robustness"). Every case must give a precise
# message, a non-zero exit (2 for usage errors, 1 for runtime failures) and write nothing:
#  1. every option of swell-bake and swell with out-of-range, negative, NaN, inf, huge and
#     malformed values, and without its value;
#  2. each KTX header field corrupted in turn, seen through `swell-bake inspect` and
#     `swell --tables`, both as a raw corruption (the manifest's file crc32 catches it) and
#     resealed (manifest crc32 updated, so the KTX reader itself must catch the field);
#  3. a bake killed with SIGKILL at random points, fresh and over an older set: whenever
#     inspect accepts the directory, it is byte-identical to a reference bake;
#  4. an unwritable output (read-only tmpfs; a parent that is a regular file) and a full one
#     (a tiny tmpfs): precise message, exit 1, no file the loader accepts, no temp file;
#  5. a FIFO in place of a manifest, a table, a preset or a shader: refused at once with what
#     it is (it had hung both programs forever, issue 17), nothing written;
#  6. the umask honoured;
#  7. a manifest edited (the seal refuses it), or edited and resealed (its values are checked
#     against physics, the state and each other), a table of another bake, extreme scale/bias;
#  8. a bake owns only what it writes: a folder with other files refused untouched, three
#     bakes at once leave one whole set, --report inside the set's folder refused.
#  9. budgets: a bake the renderer would not fit refused; the smallest accepted budget opens with
#     the patches on every tier; a set over its own or --budget refused from its manifest;
# 10. LP_NATIVE_VECTOR_WIDTH=128 on an AVX CPU (Mesa 22's llvmpipe corrupts its heap) refused.
# Mounting needs root and CAP_SYS_ADMIN; where it is refused the mount cases say why and are
# skipped, except under CI=true where that is a failure.
set -u
BUILD=${SWELL_BUILD:-build/rel}
B=$BUILD/swell-bake
S=$BUILD/swell
# sanitizer builds: tools/run-tests.sh says what swell needs preloaded (Mesa's driver)
if [ -n "${SWELL_SAN_PRELOAD:-}" ]; then
    swell() { LD_PRELOAD="$SWELL_SAN_PRELOAD" "$S" "$@"; }
else
    swell() { "$S" "$@"; }
fi
T=${SWELL_TMP:-/tmp}/bad_input
mounts=""
cleanup() {
    for m in $mounts; do umount "$m" 2>/dev/null; done
}
trap cleanup EXIT
trap 'exit 1' INT TERM
rm -rf "$T"; mkdir -p "$T"
fails=0; checks=0
for prog in "$B" "$S"; do
    if ! [ -x "$prog" ]; then
        echo "$prog is not built: run \`make test-unit\` (tools/fuzz.mk makes it depend on swell)"
        exit 1
    fi
done
ok() { checks=$((checks + 1)); echo "ok   $*"; }
bad() { checks=$((checks + 1)); fails=$((fails + 1)); echo "FAIL $*"; }
check() { # check NAME COMMAND...
    name=$1; shift
    if "$@"; then ok "$name"; else bad "$name"; fi
}
no_temp_files() { ! ls -a "$1" 2>/dev/null | grep -q '\.tmp\.'; }

t_section=$(date +%s)
# ---- 1. option catalogue ----------------------------------------------------------------------

# usage PROGRAM OPTION VALUE [PATTERN]: exit 2, the message names the option (or PATTERN),
# nothing written. The bad option comes last so it is the one refused.
usage() {
    prog=$1; opt=$2; val=$3; pat=${4:-$2}
    rm -rf "$T/never" "$T/never.png" "$T/never.json"
    if [ "$prog" = bake ]; then
        out=$("$B" --out "$T/never" --report "$T/never.json" --quiet "$opt" "$val" 2>&1); rc=$?
    else
        # "$S" itself: a usage error exits before EGL, so no driver preload is needed
        out=$("$S" --platform surfaceless --size 64x64 --frames 1 --out "$T/never.png" \
              "$opt" "$val" 2>&1); rc=$?
    fi
    if [ $rc -eq 2 ] && printf '%s' "$out" | grep -q -- "$pat" && [ ! -e "$T/never" ] &&
       [ ! -e "$T/never.png" ] && [ ! -e "$T/never.json" ]; then
        ok "$prog $opt '$val' -> $out"
    else
        bad "$prog $opt '$val': exit $rc, wanted 2 and a message naming $pat: $out"
    fi
}
# needs_value PROGRAM OPTION: the option as the last argument, without its value.
needs_value() {
    rm -rf "$T/never" "$T/never.png"
    if [ "$1" = bake ]; then out=$("$B" --out "$T/never" "$2" 2>&1); rc=$?
    else out=$("$S" --platform surfaceless --out "$T/never.png" "$2" 2>&1); rc=$?; fi
    if [ $rc -eq 2 ] && printf '%s' "$out" | grep -q -- "$2" && [ ! -e "$T/never" ] &&
       [ ! -e "$T/never.png" ]; then ok "$1 $2 without a value"
    else bad "$1 $2 without a value: exit $rc: $out"; fi
}
# numbers OPTION PROGRAM VALUES...: each value refused
values() {
    prog=$1; opt=$2; shift 2
    needs_value "$prog" "$opt"
    for v in "$@"; do usage "$prog" "$opt" "$v"; done
}

# swell-bake (the ranges are in `swell-bake --help`)
values bake --wind -5 0 0.49 40.01 nan inf 1e300 abc 5m/s "" " 5" 5,5
values bake --wind-dir -360.5 361 nan -inf 1e39 deg ""
values bake --fetch 0 -1 0.09 10001 nan inf 1e300 km ""
values bake --depth -1 0.5 10001 nan inf 1e300 deep ""
values bake --spectrum foo "" JONSWAP "jonswap " pm,tma
values bake --spread 0 -2 100.5 nan inf 1e300 x ""
values bake --seed -1 0 2147483648 99999999999999999999 1.5 1e3 0x10 abc ""
values bake --choppiness -0.1 2.1 nan inf 1e300 x ""
values bake --whitecap-model mom81 "" MOM80 wu
values bake --foam-half-life 0 -3 0.04 61 nan inf 1e300 x ""
values bake --patterns 0 -1 5 4294967297 1.5 nan x ""
values bake --period 0 -16 1.99 601 nan inf 1e300 x ""
values bake --frames 0 1 2 3 -8 257 4294967298 8.5 nan 0x10 ""
values bake --size 0 8 -64 17 48 100 2048 4294967312 64.0 nan ""
values bake --size-geo 0 4 -64 24 1024 4294967304 nan ""
values bake --budget 0 -1 1X 0.5M 1023 2G 99999999999999999999 nan lots ""
needs_value bake --preset
for v in nonexistent ../calm /nonexistent.preset "" "calm rough"; do usage bake --preset "$v" preset; done
usage bake --bogus 1 "unknown option"
out=$("$B" --wind 10 2>&1); rc=$?
check "bake without --out: exit 2 naming --out ($out)" sh -c "[ $rc -eq 2 ] && printf '%s' '$out' | grep -q -- --out"
out=$("$B" inspect 2>&1); rc=$?
check "inspect without DIR: exit 2 ($out)" [ $rc -eq 2 ]
out=$("$B" inspect "$T/a" "$T/b" 2>&1); rc=$?
check "inspect with two DIRs: exit 2 ($out)" [ $rc -eq 2 ]

# swell (the ranges are in `swell --help`)
values swell --platform x "" SURFACELESS
values swell --size 0x90 15x90 160x0 160x16385 -160x90 160x 160 x90 160x90x2 99999999999x90 \
    nanxnan 1e3x90 160.5x90 ""
values swell --frames -1 100000001 1e9 1.5 nan abc ""
values swell --fps 0 -30 0.09 1001 nan inf 1e300 abc ""
values swell --time nan inf -inf 1e300 -1e300 abc ""
values swell --duration 0 -1 nan inf 1e300 abc ""
values swell --out "" "$T/never/x%d%d.png" "$T/never/x%s.png" "$T/never/x%n.png" \
    "$T/never/x%2147483648d.png" "$T/never/x%033d.png" \
    "$T/never/x.jpg" "$T/never/x"
values swell --tables ""
values swell --device ""
values swell --connector ""
needs_value swell --tables
needs_value swell --preset
for v in nonexistent ../calm ""; do usage swell --preset "$v" preset; done
values swell --wind 0 -5 40.5 nan inf 1e300 abc ""
values swell --budget 0 -1 1X 2G nan ""
values swell --sun 0,0 -10,0 91,0 nan,0 30,nan inf,0 30 30,0,1 "" 30,,0 a,b 1e300,0
values swell --camera 0,0,0 0,0,-1 0,0,500001 nan,0,10 0,inf,10 1,2 1,2,3,4 1e39,0,10 "" a,b,c
values swell --heading -361 361 nan inf 1e300 x ""
values swell --pitch -90 90 nan inf 1e300 x ""
values swell --path 5km "" SURFACE
values swell --quality ultra "" LOW
values swell --geometry mesh "" GRID
values swell --tier gles4 "" GLES3 gles2
values swell --lod run "" PIXEL per-pixel
values swell --detile yes "" ON 1 AUTO
values swell --scale 0 -0.5 0.24 1.01 2 nan inf 1e300 50% 0.5x abc ""
out=$("$S" --platform surfaceless --size 64x64 --frames 1 --out "$T/never.png" --scale 0.5 \
      --debug variants 2>&1); rc=$?
check "swell: --scale with --debug variants is a usage error ($out)" \
    sh -c "[ $rc -eq 2 ] && ! [ -e '$T/never.png' ] && printf '%s' '$out' | grep -q -- --scale"
values swell --mode 0x0 15x480 640x480@0 640x480@1001 640x480@nan 640x480@ abc ""
values swell --kms-api modern "" ATOMIC
needs_value swell --device
needs_value swell --connector
usage swell --bogus 1 "unknown option"
# (each refused by its own check, "--mask-area: ...", not by the missing --mask)
needs_value swell --mask-area
for v in 0,0,0,10 0,0,10,-1 0,0,2e6,10 nan,0,10,10 0,inf,10,10 1,2,3 1,2,3,4,5 "" a,b,c,d; do
    usage swell --mask-area "$v" "--mask-area:"
done
usage swell --mask "" --mask
out=$("$S" --platform surfaceless --size 64x64 --frames 1 --out "$T/never.png" \
      --mask docs/lee-mask.png 2>&1); rc=$?
if [ $rc -eq 2 ] && [ ! -e "$T/never.png" ] && printf '%s' "$out" | grep -q -- --mask-area; then
    ok "swell: --mask without --mask-area is a usage error ($out)"
else bad "swell: --mask without --mask-area: exit $rc, wanted 2 naming --mask-area: $out"; fi
out=$("$S" --platform surfaceless --frames 3 --out "$T/never.png" 2>&1); rc=$?
check "swell: several frames into one file is a usage error ($out)" \
    sh -c "[ $rc -eq 2 ] && ! [ -e '$T/never.png' ] && printf '%s' '$out' | grep -q -- --out"

echo "section took $(($(date +%s) - t_section)) s"; t_section=$(date +%s)
# ---- 2. each table header field corrupted in turn -----------------------------------------------

"$B" --size 16 --size-geo 8 --frames 4 --patterns 1 --out "$T/good" --quiet ||
    bad "small reference bake"
out=$(swell --platform surfaceless --size 64x64 --frames 1 --tables "$T/good" \
      --out "$T/good.png" 2>&1); rc=$?
check "swell accepts the uncorrupted set (exit $rc)" sh -c "[ $rc -eq 0 ] && [ -s '$T/good.png' ]"
crc_of() { gzip -c "$1" | tail -c 8 | head -c 4 | od -An -tu4 | tr -d ' '; }
# reseal DIR FILE: make the manifest's size and crc32 agree with the (corrupted) file again
reseal() {
    stem=$(basename "$2" .ktx)
    i=$(sed -n "s/^table\.\([0-9]*\)\.name = $stem\$/\1/p" "$1/manifest.swell")
    sed -i "s/^table\.$i\.file_crc32 = .*/table.$i.file_crc32 = $(crc_of "$2")/;
            s/^table\.$i\.file_bytes = .*/table.$i.file_bytes = $(wc -c < "$2" | tr -d ' ')/" \
        "$1/manifest.swell"
    "$BUILD/tools/manifest-reseal" "$1/manifest.swell"
}
# refused DIR FILE WHAT: inspect and swell --tables both exit 1 naming FILE; no PNG written
refused() {
    out=$("$B" inspect "$1" 2>&1); rc=$?
    if [ $rc -eq 1 ] && printf '%s' "$out" | grep -q "$2"; then ok "inspect refuses $3"
    else bad "inspect $3: exit $rc, wanted 1 naming $2: $(printf '%s' "$out" | tail -n 1)"; fi
    rm -f "$T/never.png"
    out=$("$S" --platform surfaceless --size 64x64 --frames 1 --tables "$1" \
          --out "$T/never.png" 2>&1); rc=$?
    if [ $rc -eq 1 ] && printf '%s' "$out" | grep -q "$2" && [ ! -e "$T/never.png" ]; then
        ok "swell --tables refuses $3: $(printf '%s' "$out" | tail -n 1)"
    else bad "swell --tables $3: exit $rc, wanted 1 naming $2: $(printf '%s' "$out" | tail -n 1)"; fi
}
# put_u32 FILE OFFSET VALUE: little-endian
put_u32() {
    v=$3
    printf "$(printf '\\%03o\\%03o\\%03o\\%03o' $((v & 255)) $(((v >> 8) & 255)) \
        $(((v >> 16) & 255)) $(((v >> 24) & 255)))" |
        dd of="$1" bs=1 seek="$2" conv=notrunc 2>/dev/null
}
get_u32() { od -An -tu4 -j "$2" -N 4 "$1" | tr -d ' '; }
n=0
for field in endianness glType glTypeSize glFormat glInternalFormat glBaseInternalFormat \
             pixelWidth pixelHeight pixelDepth numberOfArrayElements numberOfFaces \
             numberOfMipmapLevels bytesOfKeyValueData; do
    offset=$((12 + 4 * n)); n=$((n + 1))
    for how in raw resealed; do
        d="$T/hdr_${field}_$how"
        cp -r "$T/good" "$d"
        f="$d/slope_p0.ktx"
        old=$(get_u32 "$f" $offset)
        put_u32 "$f" $offset $(((old + 1) & 4294967295))
        [ $how = resealed ] && reseal "$d" "$f"
        refused "$d" slope_p0.ktx "slope_p0.ktx $field $old -> $((old + 1)) ($how)"
    done
done
d="$T/hdr_identifier"; cp -r "$T/good" "$d"
printf 'KTX 20' | dd of="$d/disp_p0.ktx" bs=1 seek=1 conv=notrunc 2>/dev/null
reseal "$d" "$d/disp_p0.ktx"
refused "$d" disp_p0.ktx "disp_p0.ktx identifier (resealed)"
d="$T/hdr_kv"; cp -r "$T/good" "$d"
sed -i 's/swell\.kind/swell.kinD/' "$d/whitecap_p0.ktx"; reseal "$d" "$d/whitecap_p0.ktx"
refused "$d" whitecap_p0.ktx "whitecap_p0.ktx key swell.kind renamed (resealed)"
d="$T/hdr_texel"; cp -r "$T/good" "$d"
size=$(wc -c < "$d/fresnel.ktx")
# complement the byte, so it changes whatever it was
byte=$(od -An -tu1 -j $((size - 9)) -N 1 "$d/fresnel.ktx" | tr -d ' ')
printf "$(printf '\\%03o' $((255 - byte)))" |
    dd of="$d/fresnel.ktx" bs=1 seek=$((size - 9)) conv=notrunc 2>/dev/null
reseal "$d" "$d/fresnel.ktx"
refused "$d" fresnel.ktx "fresnel.ktx texel changed (resealed: the image crc32 catches it)"
d="$T/hdr_truncated"; cp -r "$T/good" "$d"
head -c 100 "$T/good/fresnel_eff.ktx" > "$d/fresnel_eff.ktx"; reseal "$d" "$d/fresnel_eff.ktx"
refused "$d" fresnel_eff.ktx "fresnel_eff.ktx truncated (resealed)"
d="$T/manifest_truncated"; cp -r "$T/good" "$d"
head -c 1000 "$T/good/manifest.swell" > "$d/manifest.swell"
refused "$d" manifest.swell "manifest.swell truncated"
d="$T/manifest_missing"; cp -r "$T/good" "$d"; rm "$d/manifest.swell"
refused "$d" manifest "a set without its manifest"
d="$T/unlisted"; cp -r "$T/good" "$d"; cp "$d/disp_p0.ktx" "$d/disp_p1.ktx"
refused "$d" disp_p1.ktx "an unlisted disp_p1.ktx"

echo "section took $(($(date +%s) - t_section)) s"; t_section=$(date +%s)
# ---- 3. a bake killed with SIGKILL at random points ----------------------------------------------

KILL_RUNS=${KILL_RUNS:-14}
BAKE="--size 64 --size-geo 32 --frames 8 --patterns 2 --wind 14 --seed 7 --quiet"
t0=$(date +%s%N)
# shellcheck disable=SC2086
"$B" $BAKE --out "$T/ref" || bad "reference bake for the kill test"
t1=$(date +%s%N)
ref_ms=$(((t1 - t0) / 1000000))
[ $ref_ms -lt 10 ] && ref_ms=10
"$B" --size 64 --size-geo 32 --frames 8 --patterns 2 --wind 5 --quiet --out "$T/old" ||
    bad "older bake for the kill test"
# same_set A B: B holds exactly A's files (temp files aside), byte for byte
same_set() {
    for f in "$1"/*; do cmp -s "$f" "$2/$(basename "$f")" || return 1; done
    [ "$(ls "$2" | grep -v '\.tmp\.' | wc -l)" -eq "$(ls "$1" | wc -l)" ]
}
rand() { od -An -N4 -tu4 /dev/urandom | tr -d ' '; }
accepted=0; refused_n=0; finished=0
i=0
while [ $i -lt $KILL_RUNS ]; do
    d="$T/kill$i"
    rm -rf "$d"
    # odd runs overwrite an older, complete set of other inputs (same file names)
    [ $((i % 2)) -eq 1 ] && cp -r "$T/old" "$d"
    # half the runs anywhere in the bake, half in its last 30%, where the files are written
    if [ $((i % 4)) -lt 2 ]; then delay=$(($(rand) % (ref_ms + 1)))
    else delay=$((ref_ms * 7 / 10 + $(rand) % (ref_ms * 4 / 10 + 1))); fi
    # shellcheck disable=SC2086
    "$B" $BAKE --out "$d" & pid=$!
    sleep "$(printf '%d.%03d' $((delay / 1000)) $((delay % 1000)))"
    kill -KILL $pid 2>/dev/null
    wait $pid 2>/dev/null; rc=$?
    [ $rc -eq 0 ] && finished=$((finished + 1))
    out=$("$B" inspect "$d" 2>&1); irc=$?
    if [ $irc -eq 0 ]; then
        accepted=$((accepted + 1))
        # a kill before the save began leaves the older set untouched: complete, so sound
        if same_set "$T/ref" "$d"; then
            ok "kill after ${delay} ms (bake exit $rc): accepted, identical to the reference"
        elif [ $((i % 2)) -eq 1 ] && same_set "$T/old" "$d"; then
            ok "kill after ${delay} ms (bake exit $rc): accepted, the older set left intact"
        else
            bad "kill after ${delay} ms (bake exit $rc): inspect accepted a set that is neither the reference nor the older set"
        fi
    elif [ $irc -eq 1 ] && [ $((i % 2)) -eq 1 ]; then
        bad "kill after ${delay} ms over an older set: it is no longer loadable (the new set must be swapped in whole): $(printf '%s' "$out" | tail -n 1 | cut -c 1-150)"
    elif [ $irc -eq 1 ]; then
        refused_n=$((refused_n + 1))
        ok "kill after ${delay} ms (bake exit $rc): refused: $(printf '%s' "$out" | tail -n 1 | cut -c 1-150)"
    else
        bad "kill after ${delay} ms: inspect exit $irc: $out"
    fi
    i=$((i + 1))
done
echo "kill test: reference bake ${ref_ms} ms; $KILL_RUNS kills: $accepted accepted (all identical" \
     "or failed above), $refused_n refused, $finished bakes finished before the kill"

echo "section took $(($(date +%s) - t_section)) s"; t_section=$(date +%s)
# ---- 4. unwritable and full output directories ----------------------------------------------------

SMALL="--size 16 --size-geo 8 --frames 4 --patterns 1 --quiet"
# nothing_loadable DIR: no manifest, no set inspect accepts, no temp file
# (the set is written in a folder beside, "<dir>.tmp.*": none may be left there either)
nothing_loadable() {
    ! [ -e "$1/manifest.swell" ] && ! "$B" inspect "$1" >/dev/null 2>&1 && no_temp_files "$1" &&
        no_temp_files "$(dirname "$1")"
}
old_set_intact() {
    "$B" inspect "$1" >/dev/null 2>&1 && no_temp_files "$1" && no_temp_files "$(dirname "$1")"
}
# runtime_error NAME PATTERN COMMAND...: exit 1 and a message matching PATTERN
runtime_error() {
    name=$1; pat=$2; shift 2
    out=$("$@" 2>&1); rc=$?
    if [ $rc -eq 1 ] && printf '%s' "$out" | grep -q -- "$pat"; then ok "$name: $(printf '%s' "$out" | tail -n 1)"
    else bad "$name: exit $rc, wanted 1 and '$pat': $out"; fi
}

: > "$T/afile"
# the wave mask's image: missing, not a PNG, over 254 pixels a side (a 300 x 16 frame of swell's)
runtime_error "swell --mask of a missing file" "nothere.png" \
    swell --platform surfaceless --size 64x64 --frames 1 --tables "$T/good" \
    --mask "$T/nothere.png" --mask-area 0,0,100,100 --out "$T/never.png"
runtime_error "swell --mask of a file that is no PNG" "--mask" \
    swell --platform surfaceless --size 64x64 --frames 1 --tables "$T/good" \
    --mask "$T/afile" --mask-area 0,0,100,100 --out "$T/never.png"
swell --platform surfaceless --size 300x16 --frames 1 --tables "$T/good" --out "$T/wide.png" \
    > /dev/null 2>&1
runtime_error "swell --mask of 300 x 16 pixels" "at most 254 x 254" \
    swell --platform surfaceless --size 64x64 --frames 1 --tables "$T/good" \
    --mask "$T/wide.png" --mask-area 0,0,100,100 --out "$T/never.png"
check "  ... and no frame written" [ ! -e "$T/never.png" ]
# shellcheck disable=SC2086
runtime_error "bake into a path under a regular file" "afile" \
    "$B" $SMALL --out "$T/afile/tables"
check "  ... and the file is untouched" [ ! -s "$T/afile" ]
runtime_error "swell PNG into a path under a regular file" "afile" \
    swell --platform surfaceless --size 64x64 --frames 1 --tables "$T/good" --out "$T/afile/x.png"
check "  ... and the file is untouched" [ ! -s "$T/afile" ]

mount_ok=1
mkdir -p "$T/ro" "$T/full"
if ! why=$(mount -t tmpfs -o ro,size=64k tmpfs "$T/ro" 2>&1); then
    mount_ok=0
else
    mounts="$T/ro"
    if ! why=$(mount -t tmpfs -o size=64k tmpfs "$T/full" 2>&1); then mount_ok=0
    else mounts="$mounts $T/full"; fi
fi
if [ $mount_ok -eq 0 ]; then
    echo "cannot mount a tmpfs here (needs root and CAP_SYS_ADMIN): $why"
    if [ "${CI:-}" = true ]; then bad "mount needed for the read-only/full directory cases"
    else echo "SKIP read-only and full output directory cases (not under CI=true)"; fi
else
    # shellcheck disable=SC2086
    runtime_error "bake into a read-only file system" "Read-only file system" \
        "$B" $SMALL --out "$T/ro/tables"
    check "  ... nothing created" [ -z "$(ls -A "$T/ro")" ]
    runtime_error "swell PNG into a read-only file system" "Read-only file system" \
        swell --platform surfaceless --size 64x64 --frames 1 --tables "$T/good" --out "$T/ro/x.png"
    check "  ... nothing created" [ -z "$(ls -A "$T/ro")" ]
    # shellcheck disable=SC2086
    runtime_error "bake report into a read-only file system" "Read-only file system" \
        "$B" $SMALL --out "$T/ro_report_tables" --report "$T/ro/r.json"
    check "  ... no report created" [ -z "$(ls -A "$T/ro")" ]

    # full: the small set is ~48 KiB of tables, a 64 KiB tmpfs holds part of a bigger one
    # shellcheck disable=SC2086
    runtime_error "bake into a full file system" "No space left on device" \
        "$B" --size 64 --size-geo 32 --frames 8 --patterns 2 --quiet --out "$T/full/tables"
    check "  ... nothing loadable, no temp file" nothing_loadable "$T/full/tables"
    rm -rf "$T/full/tables"
    # over an older complete set that fits: the failed bake leaves the older set as it was (the
    # new one is written beside and swapped in only when whole)
    # shellcheck disable=SC2086
    "$B" $SMALL --out "$T/full/tables" || bad "small bake into the 64 KiB tmpfs"
    "$B" inspect "$T/full/tables" >/dev/null 2>&1 || bad "the small set in the tmpfs is sound"
    runtime_error "re-bake a bigger set over it" "No space left on device" \
        "$B" --size 32 --size-geo 16 --frames 8 --patterns 2 --quiet --out "$T/full/tables"
    check "  ... the older set intact and sound, no temp file or folder" old_set_intact \
        "$T/full/tables"
    rm -rf "$T/full/tables"
    dd if=/dev/zero of="$T/full/filler" bs=4096 2>/dev/null
    runtime_error "swell PNG into a full file system" "No space left on device" \
        swell --platform surfaceless --size 256x256 --frames 1 --tables "$T/good" --out "$T/full/x.png"
    check "  ... no PNG, no temp file" sh -c "! [ -e '$T/full/x.png' ] && ! ls -a '$T/full' | grep -q tmp"
fi

# ---- 5. non-regular files: a FIFO opened for reading blocks until a writer comes -------------

# fifo_case NAME RC COMMAND...: exit RC within 30 s naming a non-regular file, nothing written
fifo_case() {
    name=$1; want=$2; shift 2
    out=$(timeout 30 "$@" 2>&1); rc=$?
    if [ $rc -eq "$want" ] && printf '%s' "$out" | grep -q "not a regular file"; then
        ok "$name: $(printf '%s' "$out" | tail -n 1)"
    else bad "$name: exit $rc (124: hung), wanted $want and 'not a regular file': $out"; fi
}
cp -r "$T/good" "$T/fifo_manifest"
rm "$T/fifo_manifest/manifest.swell"; mkfifo "$T/fifo_manifest/manifest.swell"
fifo_case "inspect with a FIFO as the manifest" 1 "$B" inspect "$T/fifo_manifest"
# swell itself (timeout cannot run the shell function), its sanitizer preload as the function has
swell_env="env ${SWELL_SAN_PRELOAD:+LD_PRELOAD=$SWELL_SAN_PRELOAD}"
# shellcheck disable=SC2086
fifo_case "swell --tables with a FIFO as the manifest" 1 $swell_env "$S" --platform surfaceless --size 64x64 --frames 1 --tables "$T/fifo_manifest" --out "$T/fifo.png"
cp -r "$T/good" "$T/fifo_table"
ktx=$(ls "$T/fifo_table"/*.ktx | head -n 1)
rm "$ktx"; mkfifo "$ktx"
fifo_case "inspect with a FIFO as a table" 1 "$B" inspect "$T/fifo_table"
# shellcheck disable=SC2086
fifo_case "swell --tables with a FIFO as a table" 1 $swell_env "$S" --platform surfaceless --size 64x64 --frames 1 --tables "$T/fifo_table" --out "$T/fifo.png"
mkfifo "$T/fifo.preset"
fifo_case "bake with a FIFO as the preset" 2 "$B" --preset "$T/fifo.preset" --out "$T/fifo_bake"
mkdir -p "$T/fifo_data"
cp -r shaders_gles tables "$T/fifo_data/"
rm "$T/fifo_data/shaders_gles/ocean.frag"; mkfifo "$T/fifo_data/shaders_gles/ocean.frag"
# shellcheck disable=SC2086
fifo_case "swell with a FIFO as a shader" 1 $swell_env SWELL_DATA_DIR="$T/fifo_data" "$S" \
    --platform surfaceless --size 64x64 --frames 1 --tables "$T/good" --out "$T/fifo.png"
check "  ... nothing written" sh -c "! [ -e '$T/fifo.png' ] && ! [ -e '$T/fifo_bake' ]"

# ---- 6. the umask: files written as open(0666) would, the umask taking its bits -------------
for m in 027 002; do
    rm -rf "$T/umask$m"
    # shellcheck disable=SC2086
    (umask $m && "$B" $SMALL --out "$T/umask$m") >/dev/null 2>&1 || bad "bake with umask $m"
    want=$(printf '%o' $((0666 & ~0$m)))
    got=$(stat -c %a "$T/umask$m/manifest.swell" 2>/dev/null)
    modes=$(stat -c %a "$T/umask$m"/*.ktx 2>/dev/null | sort -u | tr '\n' ' ')
    check "bake under umask $m: manifest $got, tables $modes(want $want)" \
        sh -c "[ '$got' = '$want' ] && [ '$modes' = '$want ' ]"
done

# ---- 7. a table set that cannot lie: the manifest's seal and its values (issue 17) ---------------
# edit DIR SED: change the manifest as a person or another program would
edited() { rm -rf "$1"; cp -r "$T/good" "$1"; sed -i "$2" "$1/manifest.swell"; }
edited "$T/seal" 's/^set.frames = .*/set.frames = 0/'
refused "$T/seal" "manifest.crc32" "an edited manifest (set.frames = 0), unsealed: the seal"
edited "$T/seal_gone" '/^manifest.crc32 = /d'
refused "$T/seal_gone" "manifest.crc32" "a manifest without its seal line"
# resealed: the values themselves are checked (set.frames = 0 had crashed swell with SIGFPE;
# a patch size of 0, -300, 1e-30 or 3e38 m drew garbage and exited 0)
for e in "set.frames = 0" "state.frames = 0" "pattern.0.size_m = 0" "pattern.0.size_m = -300" \
         "pattern.0.size_m = 1e-30" "pattern.0.size_m = 3e38" "pattern.0.k_max = 1e5" \
         "pattern.0.lambda = 1.5" "pattern.0.period_s = 1.7" "pattern.0.var_h = -1" \
         "pattern.0.mss_x = 50" "pattern.1.size_m = 10" "set.mss_unresolved_x = 50" \
         "set.hs_m = 30" "set.whitecap_fraction_model = 2" "set.foam_recovery_per_s = 0" \
         "set.whitecap_epsilon = 1e30" "table.0.layers = 2" \
         "table.0.levels = 1" "table.2.width = 16"; do
    key=${e%% =*}
    edited "$T/values" "s/^$key = .*/$e/"
    "$BUILD/tools/manifest-reseal" "$T/values/manifest.swell"
    refused "$T/values" "$key" "a resealed manifest with $e"
done
# a table of another bake (another wind), listed with its own size and crc32 and resealed: the
# file's swell.set names the sea state it was baked from
"$B" --size 16 --size-geo 8 --frames 4 --patterns 1 --wind 12 --out "$T/other" --quiet ||
    bad "a second small bake"
rm -rf "$T/mixed"; cp -r "$T/good" "$T/mixed"; cp "$T/other/slope_p0.ktx" "$T/mixed/"
reseal "$T/mixed" "$T/mixed/slope_p0.ktx"
refused "$T/mixed" "another sea state" "a table of another bake, resealed into the manifest"
# extreme but finite dequantisation in a KTX (the image crc32 does not cover the metadata)
rm -rf "$T/scale"; cp -r "$T/good" "$T/scale"
# the first scale becomes 3e+0...030, as long as the number it replaces (the file keeps its size)
perl -pi -e 's/(swell\.scale\x00)([^ ]{5,})/$1 . "3e+" . ("0" x (length($2) - 5)) . "30"/e' \
    "$T/scale/disp_p0.ktx"
reseal "$T/scale" "$T/scale/disp_p0.ktx"
refused "$T/scale" "physical range" "a displacement table scaled by 3e30, resealed"

# ---- 8. a bake owns only what it writes (issue 17 item 3) ----------------------------------------
# a folder holding anything but a table set is refused before anything is written
for f in notes.txt user.ktx slope_p9.ktx; do
    rm -rf "$T/own"; cp -r "$T/good" "$T/own"; echo mine > "$T/own/$f"
    # shellcheck disable=SC2086
    out=$("$B" $SMALL --wind 12 --out "$T/own" 2>&1); rc=$?
    check "bake into a set's folder holding $f: exit 1 naming it ($out)" \
        sh -c "[ $rc -eq 1 ] && printf '%s' '$out' | grep -q '$f'"
    check "  ... $f untouched, the set as it was" sh -c "[ \"\$(cat '$T/own/$f')\" = mine ] &&
        cmp -s '$T/good/manifest.swell' '$T/own/manifest.swell' && ! ls -a '$T' | grep -q 'own\\.tmp\\.'"
done
rm -rf "$T/own"; mkdir -p "$T/own"; ln -s /etc/hostname "$T/own/fresnel.ktx"
# shellcheck disable=SC2086
out=$("$B" $SMALL --out "$T/own" 2>&1); rc=$?
check "bake into a folder holding a symlink named as a table: exit 1 ($out)" \
    sh -c "[ $rc -eq 1 ] && [ -L '$T/own/fresnel.ktx' ]"
# three bakes into one folder at once, 10 times: all finish, the folder holds one of the sets
# whole (two had left it unloadable in 4 of 30 close starts; a bake cleaning up after killed
# ones had once taken another's new folder for one)
# shellcheck disable=SC2086
"$B" $SMALL --wind 12 --out "$T/ref12" || bad "reference bake, wind 12"
# shellcheck disable=SC2086
"$B" $SMALL --wind 7 --out "$T/ref7" || bad "reference bake, wind 7"
race_bad=0
for i in 1 2 3 4 5 6 7 8 9 10; do
    rm -rf "$T/race"
    # shellcheck disable=SC2086
    "$B" $SMALL --out "$T/race" & p1=$!
    # shellcheck disable=SC2086
    "$B" $SMALL --wind 12 --out "$T/race" & p2=$!
    # shellcheck disable=SC2086
    "$B" $SMALL --wind 7 --out "$T/race" & p3=$!
    wait $p1; r1=$?; wait $p2; r2=$?; wait $p3; r3=$?
    if [ $r1 -ne 0 ] || [ $r2 -ne 0 ] || [ $r3 -ne 0 ] ||
       ! "$B" inspect "$T/race" >/dev/null 2>&1 ||
       ! { same_set "$T/good" "$T/race" || same_set "$T/ref12" "$T/race" ||
           same_set "$T/ref7" "$T/race"; }; then
        race_bad=$((race_bad + 1))
    fi
done
check "three bakes into one folder at once, 10 times: all exit 0, one whole set ($race_bad bad)" \
    [ $race_bad -eq 0 ]
check "  ... no temporary folder left beside it" sh -c "! ls -a '$T' | grep -q 'race\\.tmp\\.'"
# --report where the set goes: refused before the bake (it would be lost with the old folder)
for r in "$T/good/r.json" "$T/good" "$T/good/"; do
    # shellcheck disable=SC2086
    out=$("$B" $SMALL --out "$T/good" --report "$r" 2>&1); rc=$?
    check "--report $r with --out $T/good: exit 2 ($out)" \
        sh -c "[ $rc -eq 2 ] && ! [ -e '$T/good/r.json' ] && [ -d '$T/good' ]"
done

# ---- 9. one budget for the renderer's GPU memory (issue 17 item 4; tables/budget.h) -------------
# a budget the renderer cannot fit on every tier and geometry kind is refused by the bake, before
# anything is written (a 2 MiB bake used to say it fitted, then --geometry patches was refused)
rm -rf "$T/b2"
out=$("$B" --budget 2M --out "$T/b2" 2>&1); rc=$?
check "bake --budget 2M: exit 1 naming the GPU memory and the budget to use ($out)" \
    sh -c "[ $rc -eq 1 ] && printf '%s' '$out' | grep -q 'GPU memory' &&
        printf '%s' '$out' | grep -q 'raise --budget' && ! [ -e '$T/b2' ]"
# the smallest budget the bake accepts opens with the patches on every tier (both qualities)
rm -rf "$T/b34"
"$B" --budget 3400000 --out "$T/b34" --quiet || bad "bake --budget 3400000"
for tier in gles2-min gles2-ext gles3; do
    for q in low high; do
        out=$(swell --platform surfaceless --size 64x64 --frames 1 --tables "$T/b34" \
              --geometry patches --tier "$tier" --quality "$q" --out "$T/b34.png" 2>&1); rc=$?
        check "a 3400000-byte set, --geometry patches, $tier $q: it fits as the bake said" \
            sh -c "[ $rc -eq 0 ] && [ -s '$T/b34.png' ]"
    done
done
# a set whose own budget the renderer cannot fit (as bakes before this check could write):
# refused by inspect and by swell from the manifest, before any table is read
edited "$T/b_over" 's/^state.budget_bytes = .*/state.budget_bytes = 2097152/'
"$BUILD/tools/manifest-reseal" "$T/b_over/manifest.swell"
rm -f "$T/b_over/slope_p0.ktx"; mkfifo "$T/b_over/slope_p0.ktx"
refused "$T/b_over" "GPU memory" "a set whose renderer needs more GPU memory than its budget"
# tables larger than the budget the manifest says they were baked for (the bake would have made
# smaller ones): refused from the manifest, before 12 MB of tables are read
rm -rf "$T/b_def"; "$B" --quiet --out "$T/b_def" || bad "a default bake"
sed -i 's/^state.budget_bytes = .*/state.budget_bytes = 8388608/' "$T/b_def/manifest.swell"
"$BUILD/tools/manifest-reseal" "$T/b_def/manifest.swell"
rm -f "$T/b_def/slope_p0.ktx"; mkfifo "$T/b_def/slope_p0.ktx"
refused "$T/b_def" "baked for" "a set whose tables exceed the budget it says it was baked for"
# swell --budget below what the set needs: refused from the manifest, no table read
rm -rf "$T/b_run"; cp -r "$T/good" "$T/b_run"
rm -f "$T/b_run/slope_p0.ktx"; mkfifo "$T/b_run/slope_p0.ktx"
out=$(swell --platform surfaceless --size 64x64 --frames 1 --tables "$T/b_run" --budget 2M \
      --out "$T/never.png" 2>&1); rc=$?
check "swell --budget 2M on a set that needs more: exit 1 naming the GPU memory, before any table ($out)" \
    sh -c "[ $rc -eq 1 ] && printf '%s' '$out' | grep -q 'GPU memory' && ! [ -e '$T/never.png' ]"

# ---- 10. a driver configuration that corrupts memory whatever is drawn (issue 17) -------------
# Mesa 22's llvmpipe with LP_NATIVE_VECTOR_WIDTH=128 on an AVX CPU aborted inside every draw
# ("free(): invalid next size"); tools/lp_width_repro.c does the same without swell. Refused
# before the first draw; where the CPU has no AVX 128 bits is llvmpipe's own width and draws.
rm -f "$T/lp.png"
out=$(LP_NATIVE_VECTOR_WIDTH=128 swell --platform surfaceless --size 64x64 --frames 1 \
      --tables "$T/good" --out "$T/lp.png" 2>&1); rc=$?
if grep -qw avx /proc/cpuinfo; then
    named=0; printf '%s' "$out" | grep -q 'unset LP_NATIVE_VECTOR_WIDTH' && named=1
    check "LP_NATIVE_VECTOR_WIDTH=128 on an AVX CPU: exit 1 naming it, no frame, no abort ($(printf '%s' "$out" | tail -n 1))" \
        sh -c "[ $rc -eq 1 ] && [ $named -eq 1 ] && ! [ -e '$T/lp.png' ]"
else
    check "LP_NATIVE_VECTOR_WIDTH=128 without AVX (llvmpipe's own width): a frame" \
        sh -c "[ $rc -eq 0 ] && [ -s '$T/lp.png' ]"
fi
out=$(LP_NATIVE_VECTOR_WIDTH=256 swell --platform surfaceless --size 64x64 --frames 1 \
      --tables "$T/good" --out "$T/lp.png" 2>&1); rc=$?
check "LP_NATIVE_VECTOR_WIDTH=256: a frame" sh -c "[ $rc -eq 0 ] && [ -s '$T/lp.png' ]"

echo "$checks checks, $fails failed"
[ $fails -eq 0 ]
