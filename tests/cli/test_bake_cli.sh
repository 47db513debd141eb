#!/bin/sh
# swell-bake end to end: help, a bake + inspect, byte-identical re-bake, the JSON report, and
# bad input (precise message, exit 2, nothing written) and corrupt tables (inspect exits 1).
set -u
B=${SWELL_BUILD:-build/rel}/swell-bake
T=${SWELL_TMP:-/tmp}/bake_cli
rm -rf "$T"; mkdir -p "$T"
fails=0
check() { # check NAME CONDITION...
    name=$1; shift
    if "$@"; then echo "ok   $name"; else echo "FAIL $name"; fails=$((fails + 1)); fi
}
expect_usage_error() { # expect_usage_error PATTERN ARGS... : exit 2, message matches, no output dir
    pat=$1; shift
    out=$("$B" "$@" --out "$T/never" 2>&1); rc=$?
    if [ $rc -eq 2 ] && printf '%s' "$out" | grep -q -- "$pat" && [ ! -e "$T/never" ]; then
        echo "ok   usage error: $* -> $out"
    else
        echo "FAIL usage error: $* (rc $rc): $out"; fails=$((fails + 1))
    fi
}

check "--help lists units" sh -c "'$B' --help | grep -q 'm/s'"
check "bake small" "$B" --wind 12 --size 32 --frames 8 --out "$T/a" --report "$T/a.json" --quiet
check "inspect ok" sh -c "'$B' inspect '$T/a' > '$T/inspect.txt'"
check "inspect lists tables" grep -q slope_p0 "$T/inspect.txt"
check "rebake" "$B" --wind 12 --size 32 --frames 8 --out "$T/b" --quiet
check "byte-identical" cmp -s "$T/a/manifest.swell" "$T/b/manifest.swell"
check "byte-identical tables" sh -c "for f in '$T'/a/*; do cmp -s \"\$f\" '$T/b/'\$(basename \"\$f\") || exit 1; done"
for key in wind_speed_mps hs_m mss_x mss_y mss_resolved mss_total whitecap_epsilon foam_recovery_per_s \
           whitecap_fraction_model whitecap_fraction_measured bytes_gpu tables; do
    check "report has $key" grep -q "\"$key\"" "$T/a.json"
done
check "no temp files left" sh -c "! ls -a '$T/a' | grep -q tmp"

expect_usage_error "--wind" --wind abc
expect_usage_error "--wind" --wind nan
expect_usage_error "--wind" --wind -5
expect_usage_error "--wind" --wind 1e300
expect_usage_error "--frames" --frames 1
expect_usage_error "--size" --size 12x
expect_usage_error "size_fs" --size 48
expect_usage_error "--budget" --budget lots
expect_usage_error "--spectrum" --spectrum foo
expect_usage_error "unknown option" --bogus 1
out=$("$B" --out "$T/never" --wind 2>&1); rc=$?
check "option without value: $out" sh -c "[ $rc -eq 2 ] && ! [ -e '$T/never' ] && printf '%s' '$out' | grep -q 'needs a value'"
out=$("$B" --wind 10 2>&1); rc=$?
check "missing --out is a usage error" sh -c "[ $rc -eq 2 ] && printf '%s' '$out' | grep -q -- --out"
out=$("$B" --size 32 --frames 8 --out "$T/norep" --report "$T/missing/r.json" 2>&1); rc=$?
check "report into a missing folder refused before baking (rc $rc)" sh -c "[ $rc -eq 2 ] && ! [ -e '$T/norep' ] && printf '%s' '$out' | grep -q -- --report"
out=$("$B" --budget 1M --size 256 --frames 64 --out "$T/over" 2>&1); rc=$?
check "over budget refused (rc $rc: $out)" sh -c "[ $rc -eq 1 ] && ! [ -e '$T/over/manifest.swell' ]"

# corrupt one byte of a table: inspect must fail and name the file
cp -r "$T/a" "$T/c"
f="$T/c/slope_p1.ktx"
size=$(wc -c < "$f")
printf '\377' | dd of="$f" bs=1 seek=$((size - 7)) conv=notrunc 2>/dev/null
out=$("$B" inspect "$T/c" 2>&1); rc=$?
check "corrupt table detected (rc $rc)" sh -c "[ $rc -ne 0 ] && printf '%s' '$out' | grep -q slope_p1"
rm "$T/c/whitecap_p0.ktx"
out=$("$B" inspect "$T/c" 2>&1); rc=$?
check "missing table detected" sh -c "[ $rc -ne 0 ] && printf '%s' '$out' | grep -q whitecap_p0"
out=$("$B" inspect "$T/nonexistent" 2>&1); rc=$?
check "missing dir detected" sh -c "[ $rc -ne 0 ]"

[ $fails -eq 0 ]
