#!/bin/bash
# validate-shaders.sh [DIR] - compile every DIR/*.vert and DIR/*.frag (default shaders_gles) with
# glslangValidator as GLSL ES 1.00 (3.00 on gles3), once per tier and quality, assembled by the
# library itself (tools/shader_source.c: gl/shader.c's header, defines and includes, as a
# device of each tier gets them); errors are mapped back to file:line the same way. Prints
# "shaders: N passed, N failed" and exits non-zero on any failure.
#
# Defines the renderer passes (shader_desc.defines) are declared in the stage file itself by
# comment lines, alternatives separated by '|', each compiled for every tier and quality:
#     // validate: FS_PATTERNS=1 | FS_PATTERNS=4 SOME_FLAG
# $SWELL_SHADER_DEFINES (NAME[=VALUE] ...) is added to every variant.
set -u
dir=${1:-shaders_gles}
src_tool=${SWELL_SHADER_SOURCE:-build/rel/tools/shader-source}
command -v glslangValidator >/dev/null 2>&1 || {
    echo "validate-shaders: glslangValidator not found; apt-get install glslang-tools" >&2
    exit 2
}
[ -x "$src_tool" ] || { echo "validate-shaders: $src_tool not built (make $src_tool)" >&2; exit 2; }
tmp=$(mktemp -d "${TMPDIR:-/tmp}/swell-shaders.XXXXXX") || exit 2
trap 'rm -rf "$tmp"' EXIT

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
            out="$tmp/x.$stage"
            tierl=$(echo "$tier" | tr 'A-Z_' 'a-z-')
            # shellcheck disable=SC2086
            set -- "$dir" "$base" "$tierl" "$quality" $variant ${SWELL_SHADER_DEFINES:-}
            if ! "$src_tool" "$@" >"$out" 2>"$tmp/err"; then
                fail=$((fail + 1)); echo "FAIL $base ($what): $(cat "$tmp/err")"
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
                printf '%s\n' "$log" | grep -E 'ERROR|WARNING' >"$tmp/log"
                "$src_tool" --map-log "$tmp/log" "$@" | sed 's/^/    /'
            fi
          done
        done
    done
done
echo "shaders: $pass passed, $fail failed"
[ "$fail" -eq 0 ]
