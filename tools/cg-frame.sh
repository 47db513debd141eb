#!/bin/bash
# cg-frame.sh - swell's own CPU instructions per frame for one set of swell options, counted as
# make bench counts them (tools/bench.sh): callgrind with collection on only inside swell's own
# per-frame functions (bench.sh's cg_own), on softpipe, two runs of N and 2N frames whose
# difference over N cancels the start-up. For an A/B of one option beside its baseline, run it
# twice in one sitting (instruction counts do not depend on the machine's load).
#
# usage: tools/cg-frame.sh [-n N] SWELL_OPTION...
#   e.g. tools/cg-frame.sh --tier gles2-min --preset moderate --camera -1100,-700,220 \
#            --heading 40 --pitch -22 --sun 30,60 --mask docs/lee-mask.png \
#            --mask-area -1280,-1280,2560,2560
# SWELL_BUILD (build/rel) names the build; the frames are 64x36 unless the options say
# otherwise. Prints each function's instructions per frame and their sum.
set -euo pipefail
n=4
if [ "${1:-}" = -n ]; then n=$2; shift 2; fi
build=${SWELL_BUILD:-build/rel}
own=$(sed -n 's/^cg_own="\(.*\)"$/\1/p' "$(dirname "$0")/bench.sh")
[ -n "$own" ] || { echo "cg-frame: no cg_own list in tools/bench.sh" >&2; exit 1; }
command -v valgrind >/dev/null || { echo "cg-frame: valgrind is missing (make deps-test)" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
toggles=()
for f in $own; do toggles+=(--toggle-collect="$f"); done
run() {   # run FRAMES OUT SWELL_OPTION...
    local frames=$1 out=$2
    shift 2
    GALLIUM_DRIVER=softpipe valgrind --tool=callgrind --collect-atstart=no "${toggles[@]}" \
        --callgrind-out-file="$out" "$build/swell" --platform surfaceless --size 64x36 \
        --frames "$frames" --fps 30 --out "$tmp/frame%d.png" "$@" > "$tmp/log" 2>&1 ||
        { echo "cg-frame: swell failed:" >&2; tail -n 5 "$tmp/log" >&2; exit 1; }
}
costs() {   # costs OUT -> "function instructions", the largest inclusive entry per name
    callgrind_annotate --inclusive=yes --auto=no --threshold=100 "$1" 2>/dev/null |
        awk -f "$(dirname "$0")/cg-costs.awk"
}
run "$n" "$tmp/a.out" "$@"
run $((2 * n)) "$tmp/b.out" "$@"
awk -v own="$own" -v n="$n" '
    FNR == 1 { k++ }
    { if (k == 1) a[$1] = $2; else b[$1] = $2 }
    END {
        split(own, o, " "); s = 0
        for (i = 1; i in o; i++) {
            d = ((o[i] in b) ? b[o[i]] : 0) - ((o[i] in a) ? a[o[i]] : 0)
            if (d != 0) printf "%-22s %8.3f M a frame\n", o[i], d / n / 1e6
            s += d
        }
        printf "%-22s %8.3f M a frame\n", "total", s / n / 1e6
    }' <(costs "$tmp/a.out") <(costs "$tmp/b.out")
