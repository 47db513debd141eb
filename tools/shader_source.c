/* shader_source.c - the shader assembler of the library (gl/shader.h), for tools: prints one
 * stage as a device of a tier sees it (the header, the defines, includes inlined with #line
 * directives), or maps a compiler's log of that source back to file:line.
 * tools/validate-shaders.sh runs every stage through glslangValidator with it, so the shaders
 * are assembled in one place.
 *
 *   shader-source DIR FILE TIER [DEFINES...]                 the source, to stdout
 *   shader-source --map-log LOG DIR FILE TIER [DEFINES...]   LOG's locations as dir/file:line
 *
 * TIER: gles2-min | gles2-ext | gles3, as a device offering every feature of the tier (gles2-ext
 * with both GLES 2 extensions; mediump fragment shaders, as on the GPUs). FILE's suffix names
 * the stage (.vert, .frag).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "core/fsutil.h"
#include "gl/shader.h"

static int usage(void)
{
    fprintf(stderr, "usage: shader-source [--map-log LOG] DIR FILE TIER [DEFINES...]\n");
    return 2;
}

int main(int argc, char **argv)
{
    const char *log_path = NULL;
    int i = 1;
    if (i + 1 < argc && !strcmp(argv[i], "--map-log")) {
        log_path = argv[i + 1];
        i += 2;
    }
    if (argc - i < 3)
        return usage();
    const char *dir = argv[i], *file = argv[i + 1];
    int tier = gpu_tier_from_name(argv[i + 2]);
    size_t n = strlen(file);
    int frag = n > 5 && !strcmp(file + n - 5, ".frag");
    int vert = n > 5 && !strcmp(file + n - 5, ".vert");
    if (tier < 0 || !(frag || vert))
        return usage();
    char defines[4096] = "";
    for (int k = i + 3; k < argc; k++) {
        size_t used = strlen(defines);
        snprintf(defines + used, sizeof defines - used, "%s%s", used ? " " : "", argv[k]);
    }
    struct gpu_caps caps = {
        .tier = tier, .tier_available = tier,
        .texture_units = 8, .vertex_texture_units = tier == TIER_GLES2_MIN ? 0 : 4,
        .derivatives = tier != TIER_GLES2_MIN, .texture_lod = tier != TIER_GLES2_MIN,
        .glsl300 = tier == TIER_GLES3,
        .glsl100_derivatives = tier == TIER_GLES2_EXT, .glsl100_texture_lod = tier == TIER_GLES2_EXT,
        .max_texture_size = 2048,
    };
    struct shader_desc d = {
        .dir = dir, .vs_file = file, .fs_file = file, .defines = defines, .caps = &caps,
    };
    GLenum stage = frag ? GL_FRAGMENT_SHADER : GL_VERTEX_SHADER;
    struct swell_err err = { 0 };
    char *out = NULL;
    int rc;
    if (log_path) {
        uint8_t *log = NULL;
        size_t len = 0;
        rc = fs_read_file(log_path, 1 << 24, &log, &len, &err);
        if (!rc)
            rc = shader_map_log(&d, stage, (const char *)log, &out, &err);
        free(log);
    } else {
        rc = shader_assemble(&d, stage, &out, &err);
    }
    if (rc) {
        fprintf(stderr, "shader-source: %s\n", err.msg);
        return 1;
    }
    fputs(out, stdout);
    free(out);
    return 0;
}
