#!/bin/sh
# run-tests.sh SUITE BUILD_DIR BIN... - run test programs, print each result and a final
# "N passed, N failed, N skipped" line (exit 77 = skip); exit non-zero if any failed. Test
# programs run from the repo root with SWELL_BUILD set so they can find the programs and a
# scratch directory.
set -u
suite=$1; build=$2; shift 2
export SWELL_BUILD="$build"
# Read only by sanitizer builds (make SAN=address,...): LeakSanitizer ignores leaks inside
# Mesa/LLVM (tools/lsan.supp says why); UBSan prints a stack. Callers may override either.
export LSAN_OPTIONS="${LSAN_OPTIONS:-suppressions=$(pwd)/tools/lsan.supp:print_suppressions=0}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1}"
# AddressSanitizer builds: Mesa dlclose()s its driver before LeakSanitizer reports at exit, so
# the driver's own leaks (tools/lsan.supp) show as unnamed frames no suppression can match.
# Preloading the driver keeps it mapped and named. libasan must stay first in the preload list
# when the runtime is a shared library (gcc). Test programs get it directly; scripts get
# SWELL_SAN_PRELOAD and pass it to the swell runs only (sh, sed, ... must not load ASan).
preload=""
if grep -qa __asan_init "$build/swell-bake" 2>/dev/null; then
    # the driver of the build's own architecture (make test-cross installs arm64's beside it)
    multi=$(ldd "$build/swell-bake" 2>/dev/null |
            sed -n 's|.*/lib/\([^/ ]*-linux-gnu[^/ ]*\)/libc\.so.*|\1|p' | head -n 1)
    drv=""
    for d in ${multi:+/usr/lib/$multi/dri/swrast_dri.so} /usr/lib/*/dri/swrast_dri.so \
             /usr/lib/dri/swrast_dri.so; do
        [ -z "$drv" ] && [ -e "$d" ] && drv=$d
    done
    asan=$(ldd "$build/swell-bake" 2>/dev/null | sed -n 's/.*libasan[^ ]* => \([^ ]*\).*/\1/p')
    [ -n "$drv" ] && preload="${asan:+$asan:}$drv"
fi
export SWELL_SAN_PRELOAD="$preload"
export SWELL_TMP="$build/tmp/$suite"
rm -rf "$SWELL_TMP"; mkdir -p "$SWELL_TMP"
pass=0; fail=0; skip=0; failed=""
for t in "$@"; do
    name=$(basename "$t")
    log="$SWELL_TMP/$name.log"
    case "$t" in
        *.sh) "$t" >"$log" 2>&1; rc=$? ;;
        # SWELL_EXEC: a runner for programs of another architecture (qemu-aarch64, make
        # test-cross)
        *) LD_PRELOAD="${preload:-${LD_PRELOAD:-}}" ${SWELL_EXEC:-} "$t" >"$log" 2>&1; rc=$? ;;
    esac
    if [ "$rc" -eq 0 ]; then
        pass=$((pass + 1)); echo "PASS $suite/$name"
    elif [ "$rc" -eq 77 ]; then
        # 77: the automake convention for "cannot run here" (no EGL device); the test itself
        # refuses to skip under CI=true.
        skip=$((skip + 1)); echo "SKIP $suite/$name: $(tail -n 1 "$log")"
    else
        fail=$((fail + 1)); failed="$failed $name"; echo "FAIL $suite/$name (log follows)"
        sed 's/^/    /' "$log" | tail -n 60
    fi
done
echo "$suite: $pass passed, $fail failed, $skip skipped"
[ "$fail" -eq 0 ]
