#!/bin/bash
# plot-bench.sh RESULTS.json OUT.png - median frame time against camera altitude, one line per
# tier and quality (the mean over the sea states), and the baseline quad, from tools/bench.sh's
# results (the scenes as swell draws them by default, --detile auto: the lattice of random offsets
# on in high quality, off in low). Needs jq and gnuplot (Debian gnuplot-nox).
set -eu
results=$1
png=$2
tmp=$(mktemp -d "${TMPDIR:-/tmp}/swell-plot.XXXXXX")
trap 'rm -rf "$tmp"' EXIT

# Camera altitude of each scripted path (src/core/camera.c camera_path_at), m.
jq -r '
  def alt: if . == "surface" then 5 elif . == "1km" then 1000 elif . == "10km" then 10000 else null end;
  [.scenes[] | select(.error == null and .ms_median != null and ((.detile // "on") == "on") == (.quality == "high"))] as $s |
  ($s | group_by(.tier, .quality)[] |
     "# \(.[0].tier) \(.[0].quality)",
     (group_by(.path)[] | "\(.[0].path | alt) \(map(.ms_median) | add / length) \(map(.ms_p95) | add / length)"),
     "", ""),
  "# quad baseline",
  ($s | group_by(.path)[] | "\(.[0].path | alt) \(map(.baseline_quad_ms) | add / length) 0"),
  ""' "$results" >"$tmp/data"
jq -r '[.scenes[] | select(.error == null and .ms_median != null and ((.detile // "on") == "on") == (.quality == "high"))] | group_by(.tier, .quality)[] |
       "\(.[0].tier) \(.[0].quality)"' "$results" >"$tmp/titles"
n=$(wc -l <"$tmp/titles")
[ "$n" -gt 0 ] || { echo "plot-bench: no measured scenes in $results" >&2; exit 1; }
subtitle=$(jq -r '"\(.size), \([.scenes[] | .gl_renderer // empty] | first // ""), \(.generated)"' "$results")

{
    echo "set terminal pngcairo size 960,600 font 'sans,10'"
    echo "set output '$png.tmp'"
    echo "set title \"swell: median frame time against camera altitude\\n{/*0.8 $subtitle}\""
    echo "set logscale x"
    echo "set logscale y"
    echo "set xlabel 'camera altitude, m (paths surface, 1km, 10km)'"
    echo "set ylabel 'ms per frame (median; glFinish per frame)'"
    echo "set xrange [3:16000]"
    echo "set grid"
    echo "set key outside right"
    printf "plot "
    i=0
    while read -r tier quality; do
        dt=1; [ "$quality" = low ] && dt=2
        pt=7; [ "$tier" = gles2-ext ] && pt=5; [ "$tier" = gles3 ] && pt=9
        printf "'%s' index %d using 1:2 with linespoints dt %d pt %d lw 2 title '%s %s', " \
            "$tmp/data" "$i" "$dt" "$pt" "$tier" "$quality"
        i=$((i + 1))
    done <"$tmp/titles"
    printf "'%s' index %d using 1:2 with lines lc rgb 'black' dt 3 lw 1 title 'baseline quad'\n" \
        "$tmp/data" "$i"
} >"$tmp/plot.gp"
gnuplot "$tmp/plot.gp"
mv "$png.tmp" "$png"
