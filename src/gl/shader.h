/* shader.h - GLSL ES 1.00 program loader (STYLE.md 8).
 *
 * Reads DIR/VS and DIR/FS, inlines `#include "x.glsl"` lines (same directory, nested up to
 * SHADER_MAX_INCLUDE_DEPTH, each file at most once per stage, a cycle is an error), and
 * prepends, in this order:
 *     #version 100
 *     #extension lines the tier allows (fragment stage: GL_OES_standard_derivatives,
 *                                        GL_EXT_shader_texture_lod)
 *     #define SWELL_TIER_GLES2_MIN 1 | SWELL_TIER_GLES2_EXT 1 | SWELL_TIER_GLES3 1
 *     #define SWELL_HAS_DERIVATIVES 1, SWELL_HAS_TEXTURE_LOD 1, SWELL_HAS_VTF 1 (when usable)
 *     #define SWELL_VERTEX_SHADER 1 | SWELL_FRAGMENT_SHADER 1
 *     the caller's defines
 *     precision highp float;   (fragment, only when the caller defines SWELL_HIGHP and the
 *                               tier has highp fragment floats; SWELL_HAS_HIGHP is then defined)
 *     precision mediump float; (fragment, otherwise)
 * `#line N F` directives keep driver messages mapped to file and line: a compile error reads
 * "shaders_gles/ocean.frag:42: <driver message>". tools/validate-shaders.sh compiles this very
 * assembly (tools/shader_source.c) with glslang for every tier.
 */
#ifndef SWELL_SHADER_H
#define SWELL_SHADER_H

#include <GLES2/gl2.h>
#include "core/err.h"
#include "gl/gpu.h"

#define SHADER_MAX_INCLUDE_DEPTH 8
#define SHADER_MAX_FILES 32          /* distinct files (with includes) per stage */

struct shader_attrib {
    const char *name;
    GLuint index;                    /* bound with glBindAttribLocation before linking */
};

struct shader_desc {
    const char *dir;                 /* NULL: shaders_gles/ found by core/datadir.h */
    const char *vs_file, *fs_file;   /* names inside dir, e.g. "ocean.vert"; required */
    /* Caller defines: whitespace-separated "NAME" or "NAME=VALUE" (no spaces in VALUE), e.g.
     * "QUALITY_HIGH PATTERNS=4". NULL = none. */
    const char *defines;
    const struct gpu_caps *caps;     /* tier in force; required */
    const char *const *uniform_names;/* enum-indexed table, uniform_count entries */
    int uniform_count;
    GLint *uniform_locations;        /* caller's array of uniform_count, filled on success;
                                        -1 where the linker dropped an unused uniform */
    const struct shader_attrib *attribs;
    int attrib_count;
};

struct shader_program {
    GLuint program;                  /* 0 = none */
};

/* The gles3 tier compiles as GLSL ES 3.00 (names of 1.00 mapped); fragment shaders then have
 * SWELL_HAS_DERIVATIVES and SWELL_HAS_TEXTURE_LOD (texture2DGradEXT), as with both GLES 2
 * extensions. */
int  shader_is_es3(const struct gpu_caps *c);
int  shader_has_gradients(const struct gpu_caps *c);

/* Build and link; on failure `out->program` is 0 and err says file:line and the driver log. */
int  shader_program_build(const struct shader_desc *d, struct shader_program *out,
                          struct swell_err *err);
void shader_program_destroy(struct shader_program *p);

/* 1 when SWELL_SHADER_LABELS=1: builds and probe draws are labelled on stderr
 * ("swell-program: begin / probe / end"), so tools/devices.py can tell which program a
 * driver's statistics belong to. */
int  shader_labels(void);

/* The assembled source of one stage (header + inlined includes with #line directives), as the
 * driver sees it; malloc'd, caller frees. stage: GL_VERTEX_SHADER or GL_FRAGMENT_SHADER. */
int  shader_assemble(const struct shader_desc *d, GLenum stage, char **source,
                     struct swell_err *err);
/* A compiler's log for that stage ("S:L(C): msg" from Mesa, "ERROR: S:L: msg" from glslang and
 * others) with every location as "dir/file:L: " of the file it is in; malloc'd, caller frees. */
int  shader_map_log(const struct shader_desc *d, GLenum stage, const char *log, char **mapped,
                    struct swell_err *err);

#endif
