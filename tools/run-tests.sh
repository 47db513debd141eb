#!/bin/sh
# run-tests.sh SUITE BUILD_DIR BIN... - run test programs, print each result and a final
# "N passed, N failed, N skipped" line (exit 77 = skip); exit non-zero if any failed. Test
# programs run from the repo root with SWELL_BUILD set so they can find the programs and a
# scratch directory.
set -u
suite=$1; build=$2; shift 2
export SWELL_BUILD="$build"
export SWELL_TMP="$build/tmp/$suite"
rm -rf "$SWELL_TMP"; mkdir -p "$SWELL_TMP"
pass=0; fail=0; skip=0; failed=""
for t in "$@"; do
    name=$(basename "$t")
    log="$SWELL_TMP/$name.log"
    "$t" >"$log" 2>&1; rc=$?
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
