#!/bin/sh
# valgrind.sh [BUILD_DIR] - memcheck of a small bake and of a short surfaceless run of swell
# (`make valgrind`). Fails on any memcheck error and on definite or indirect leaks; "still
# reachable" (FFTW's wisdom cache, Mesa's driver state) is not a leak. Suppressions: only
# tools/valgrind.supp, which covers Mesa/EGL/LLVM's own code, each entry explained there.
# llvmpipe runs single-threaded (LP_NUM_THREADS=0) so its JIT threads do not multiply the run
# time under valgrind; the code swell runs is the same.
set -u
build=${1:-build/rel}
tmp=$build/tmp/valgrind
rm -rf "$tmp"; mkdir -p "$tmp"
if ! command -v valgrind >/dev/null 2>&1; then
    echo "valgrind.sh: valgrind is not installed (tools/install-deps.sh installs it)" >&2
    exit 1
fi
# --keep-debuginfo: Mesa dlclose()s its driver at exit, and leaks it made would otherwise show
# as "???" frames no suppression can name.
VG="valgrind --error-exitcode=99 --leak-check=full --show-leak-kinds=definite,indirect
    --errors-for-leak-kinds=definite,indirect --num-callers=40
    --keep-debuginfo=yes --suppressions=tools/valgrind.supp"
fail=0
run() { # run NAME COMMAND...
    name=$1; shift
    log="$tmp/$name.log"
    start=$(date +%s)
    # shellcheck disable=SC2086
    $VG "$@" >"$log" 2>&1; rc=$?
    secs=$(($(date +%s) - start))
    summary=$(grep -E 'ERROR SUMMARY' "$log" | tail -n 1 | sed 's/^==[0-9]*== //')
    if [ $rc -eq 0 ]; then
        echo "PASS valgrind/$name (${secs} s): $summary"
    else
        fail=1
        echo "FAIL valgrind/$name (exit $rc, ${secs} s): $summary; log: $log"
        grep -E '^==[0-9]+== (Invalid|Conditional|Use of|Syscall|Mismatched|[0-9,]+ bytes in)' \
            "$log" | head -n 10
    fi
}
run bake "$build/swell-bake" --size 32 --size-geo 16 --frames 4 --patterns 2 --quiet \
    --out "$tmp/tables"
if [ -x "$build/swell" ]; then
    # the bake above may have failed; the render then bakes its own small set in memory
    if [ -f "$tmp/tables/manifest.swell" ]; then src="--tables $tmp/tables"
    else src="--wind 10 --budget tiny"; fi
    # shellcheck disable=SC2086
    LP_NUM_THREADS=0 run swell "$build/swell" --platform surfaceless --size 160x90 --frames 2 \
        --tier gles2-min $src --out "$tmp/frame%d.png"
fi
exit $fail
