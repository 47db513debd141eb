#!/bin/bash
# validate-shaders.sh [DIR] - compile every DIR/*.vert and DIR/*.frag (default shaders_gles) with
# glslangValidator as GLSL ES 1.00, once per tier and quality, with the header src/gl/shader.c
# prepends (keep the two in step: src/gl/shader.h lists it) and includes inlined the same way
# (same directory, each file once, depth limit 8). Errors are mapped back to file:line through
# the same #line encoding (line = file_index * 100000 + line). Prints
# "shaders: N passed, N failed" and exits non-zero on any failure.
#
# Defines the renderer passes (shader_desc.defines) are declared in the stage file itself by
# comment lines, alternatives separated by '|', each compiled for every tier and quality:
#     // validate: FS_PATTERNS=1 | FS_PATTERNS=4 SOME_FLAG
# $SWELL_SHADER_DEFINES (NAME[=VALUE] ...) is added to every variant.
set -u
dir=${1:-shaders_gles}
command -v glslangValidator >/dev/null 2>&1 || {
    echo "validate-shaders: glslangValidator not found; apt-get install glslang-tools" >&2
    exit 2
}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/swell-shaders.XXXXXX") || exit 2
trap 'rm -rf "$tmp"' EXIT

files=()        # index -> file name; 0 is the generated header
max_depth=8

# emit FILE DEPTH: print FILE with includes inlined and #line directives, to stdout.
emit() {
    local file=$1 depth=$2 idx n=0 line name
    idx=${#files[@]}
    files+=("$file")
    if [ ! -f "$dir/$file" ]; then
        echo "validate-shaders: $dir/$file: no such file" >&2
        return 1
    fi
    echo "#line $((idx * 100000 + 1)) $idx"
    while IFS= read -r line || [ -n "$line" ]; do
        n=$((n + 1))
        if [[ $line =~ ^[[:space:]]*#[[:space:]]*include[[:space:]]*\"([^\"/]+)\"[[:space:]]*$ ]]; then
            name=${BASH_REMATCH[1]}
            if [[ " ${files[*]} " == *" $name "* ]]; then
                echo ""
                continue
            fi
            if [ "$depth" -ge "$max_depth" ]; then
                echo "$dir/$file:$n: #include nested deeper than $max_depth (or a cycle)" >&2
                return 1
            fi
            emit "$name" $((depth + 1)) || return 1
            echo "#line $((idx * 100000 + n + 1)) $idx"
        elif [[ $line =~ ^[[:space:]]*#[[:space:]]*include ]]; then
            echo "$dir/$file:$n: malformed #include" >&2
            return 1
        else
            printf '%s\n' "$line"
        fi
    done <"$dir/$file"
}

# header STAGE TIER QUALITY: what shader.c's emit_header writes for a device offering every
# feature of TIER (gles2-ext and gles3 assume both extensions present, as on Mesa).
header() {
    local stage=$1 tier=$2 quality=$3
    if [ "$tier" = GLES3 ]; then
        # GLSL ES 3.00 with the 1.00 names mapped (src/gl/shader.c emit_header)
        echo "#version 300 es"
        echo "#define texture2D texture"
        echo "#define texture2DLod textureLod"
        echo "#define texture2DGradEXT textureGrad"
        echo "#define texture2DLodEXT textureLod"
        if [ "$stage" = frag ]; then
            echo "#define varying in"
            echo "out highp vec4 swell_frag_colour;"
            echo "#define gl_FragColor swell_frag_colour"
        else
            echo "#define attribute in"
            echo "#define varying out"
        fi
    else
        echo "#version 100"
    fi
    if [ "$stage" = frag ] && [ "$tier" = GLES2_EXT ]; then
        echo "#extension GL_OES_standard_derivatives : enable"
        echo "#extension GL_EXT_shader_texture_lod : enable"
    fi
    echo "#define SWELL_TIER_$tier 1"
    if [ "$tier" != GLES2_MIN ]; then
        if [ "$stage" = frag ]; then
            echo "#define SWELL_HAS_DERIVATIVES 1"
            echo "#define SWELL_HAS_TEXTURE_LOD 1"
        fi
        echo "#define SWELL_HAS_VTF 1"
    fi
    if [ "$stage" = frag ]; then echo "#define SWELL_FRAGMENT_SHADER 1"; else echo "#define SWELL_VERTEX_SHADER 1"; fi
    echo "#define $quality 1"
    local d
    for d in $4 ${SWELL_SHADER_DEFINES:-}; do
        if [[ $d == *=* ]]; then echo "#define ${d%%=*} ${d#*=}"; else echo "#define $d 1"; fi
    done
    [ "$stage" = frag ] && echo "precision mediump float;"
    return 0
}

pass=0; fail=0
shopt -s nullglob
for src in "$dir"/*.vert "$dir"/*.frag; do
    base=$(basename "$src")
    stage=${base##*.}
    spec=$(sed -n 's|^[[:space:]]*//[[:space:]]*validate:||p' "$src" | tr '\n' ' ')
    IFS='|' read -r -a variants <<<"${spec:- }"
    for tier in GLES2_MIN GLES2_EXT GLES3; do
        for quality in QUALITY_HIGH QUALITY_LOW; do
          for variant in "${variants[@]}"; do
            variant=$(echo $variant)
            what="$tier $quality${variant:+ $variant}"
            files=("<swell header>")
            out="$tmp/x.$stage"
            if ! { header "$stage" "$tier" "$quality" "$variant"; emit "$base" 0; } >"$out"; then
                fail=$((fail + 1)); echo "FAIL $base ($what): include error"
                continue
            fi
            if log=$(glslangValidator "$out" 2>&1); then
                pass=$((pass + 1))
                # GLES 2 guarantees 8 varying vectors (GLES 3: 16): count the rows the
                # variant's varyings take, packed as GLSL ES 1.00 Appendix A.7 does
                # (tools/varyings.awk), and refuse a variant a minimal device cannot link
                if [ "$stage" = vert ] && [ "$tier" != GLES3 ]; then
                    rows=$(glslangValidator -E "$out" 2>/dev/null | awk -f tools/varyings.awk)
                    if [ "${rows:-99}" -gt 8 ]; then
                        pass=$((pass - 1)); fail=$((fail + 1))
                        echo "FAIL $base ($what): its varyings take $rows rows of GLES 2's 8"
                    fi
                fi
            else
                fail=$((fail + 1))
                echo "FAIL $base ($what):"
                names="${files[*]}"
                printf '%s\n' "$log" | grep -E 'ERROR|WARNING' | awk -v dir="$dir" -v names="$names" '
                    BEGIN { n = split(names, f, " "); }
                    {
                        if (match($0, /[0-9]+:[0-9]+:/)) {
                            split(substr($0, RSTART, RLENGTH - 1), a, ":");
                            idx = int(a[2] / 100000); ln = a[2] % 100000;
                            name = (idx > 0 && idx + 2 <= n) ? dir "/" f[idx + 2] : "<swell header>";
                            if (idx == 0) ln = a[2];
                            print "    " name ":" ln ":" substr($0, RSTART + RLENGTH);
                        } else print "    " $0;
                    }'
            fi
          done
        done
    done
done
echo "shaders: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
