#!/bin/bash
# cg-frame.sh SHADER_PARENT [swell options...] - llvmpipe instructions per whole frame, by
# callgrind: `swell --bench --warmup 0` with LP_NUM_THREADS=0 (deterministic), its PROGRAM TOTALS
# at --frames 4 minus --frames 1, over 3, after one run that fills Mesa's shader cache. Runs from
# SHADER_PARENT, so its shaders_gles/ is the one drawn: a copy with a part taken out gives that
# part's cost (docs/measurements.md, Performance). Defaults: 320x180, rough tables from make bench
# (build/bench/tables/rough), camera 0,0,10 pitch -10, time 0; later options override them.
# Needs valgrind. Not beside other GL work: tests that compile many shaders evict Mesa's cache,
# and a recompile counted in one of the two runs gave 668 M for a 61 M frame.
set -eu
here=$(cd "$(dirname "$0")/.." && pwd)
dir=$(cd "${1:?usage: cg-frame.sh SHADER_PARENT [swell options...]}" && pwd); shift
swell="${SWELL:-$here/build/rel/swell}"
tables="${TABLES:-$here/build/bench/tables/rough}"
tmp=$(mktemp -d "${TMPDIR:-/tmp}/swell-cg.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
count() {   # count FRAMES SWELL_OPTIONS... -> PROGRAM TOTALS
    local n=$1; shift
    (cd "$dir" && LP_NUM_THREADS=0 valgrind --tool=callgrind --callgrind-out-file="$tmp/cg" \
        "$swell" --platform surfaceless --size 320x180 --tables "$tables" --camera 0,0,10 \
        --pitch -10 --time 0 --bench --warmup 0 --frames "$n" "$@" >/dev/null 2>&1) ||
        { echo "cg-frame: swell failed under callgrind" >&2; exit 1; }
    callgrind_annotate "$tmp/cg" 2>/dev/null | awk '/PROGRAM TOTALS/ { gsub(",", "", $1); print $1 }'
}
count 1 "$@" >/dev/null   # fills the shader cache
a=$(count 1 "$@")
b=$(count 4 "$@")
echo "cg-frame: $* : $(( (b - a) / 3 )) instructions per frame"
