# cg-costs.awk - callgrind_annotate --inclusive=yes output -> "function instructions" lines, the
# largest entry per function name (a function's inclusive cost; tools/bench.sh, cg-frame.sh).
/^ *[0-9,]+ \([ 0-9.]+%\) +[^ ]+:[A-Za-z_]/ {
    c = $1; gsub(/,/, "", c); f = $0; sub(/^ *[0-9,]+ \([ 0-9.]+%\) +[^ ]*:/, "", f)
    sub(/[ .].*/, "", f)
    if (!(f in m) || c + 0 > m[f]) m[f] = c + 0
}
END { for (f in m) print f, m[f] }
