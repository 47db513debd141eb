# varyings.awk: GLSL ES 1.00 Appendix A.7 packing of the varyings in preprocessed source,
# conservatively: vec4 / mat rows whole, each vec3 a row (its 4th column free for a float),
# vec2 two to a row, floats into free columns, then four to a row. Prints the rows used.
/^[[:space:]]*varying[[:space:]]/ {
    line = $0
    sub(/\/\/.*/, "", line)
    gsub(/(lowp|mediump|highp)[[:space:]]+/, "", line)
    n = split(line, w, /[[:space:],;]+/)
    for (i = 1; i <= n; i++) if (w[i] == "varying") { type = w[i + 1]; first = i + 2; break }
    for (i = first; i <= n; i++) {
        if (w[i] == "") continue
        size = 1
        if (match(w[i], /\[[0-9]+\]/)) size = substr(w[i], RSTART + 1, RLENGTH - 2) + 0
        if (type == "vec4") r4 += size
        else if (type == "mat2") r4 += 2 * size
        else if (type == "mat3") r4 += 3 * size
        else if (type == "mat4") r4 += 4 * size
        else if (type == "vec3") r3 += size
        else if (type == "vec2") r2 += size
        else if (type == "float") r1 += size
    }
}
END {
    rows = r4 + r3 + int((r2 + 1) / 2)
    free = r3 + (r2 % 2 ? 2 : 0)
    rest = r1 > free ? r1 - free : 0
    rows += int((rest + 3) / 4)
    print rows
}
