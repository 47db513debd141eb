#!/bin/bash
# test_run_sh.sh - the bake step of `make run` (tools/run.sh) on a fresh tree: the tables folder
# and its parent do not exist yet. (A regression: swell-bake refuses a --report into a missing
# folder before baking, and run.sh had not created it, so `make run` failed on a clean clone.)
# The renderer is left out (a build folder holding only swell-bake), so run.sh stops after
# baking; the frames themselves are the frame tests' business.
set -u
BUILD=${SWELL_BUILD:-build/rel}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/swell-run.XXXXXX") || exit 1
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/build"
ln -s "$(cd "$BUILD" && pwd)/swell-bake" "$tmp/build/swell-bake"
fail=0
out=$(tools/run.sh "$tmp/build" "$tmp/fresh/tables/default" 2>&1)
rc=$?
if [ $rc -ne 0 ]; then
    echo "FAIL: run.sh exited $rc on a fresh tree: $out"; fail=1
fi
if ! "$BUILD/swell-bake" inspect "$tmp/fresh/tables/default" >/dev/null 2>&1; then
    echo "FAIL: no valid table set in $tmp/fresh/tables/default"; fail=1
fi
if [ ! -s "$tmp/fresh/tables/default.json" ]; then
    echo "FAIL: no bake report beside the tables"; fail=1
fi
case $out in
    *"renderer is not built"*) ;;
    *) echo "FAIL: run.sh did not stop after baking: $out"; fail=1 ;;
esac
[ $fail -eq 0 ] && echo "run.sh: fresh-tree bake step ok"
exit $fail
