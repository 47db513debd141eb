/* glapp.c - the programs' own GL objects (glapp.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/glapp.h"
#include "core/datadir.h"
#include "core/err.h"
#include "core/fsutil.h"

const char *glapp_tier_name(int swell_tier)
{
    static const char *const names[] = { "best", "gles2-min", "gles2-ext", "gles3" };
    return swell_tier >= 0 && swell_tier <= SWELL_TIER_GLES3 ? names[swell_tier] : "?";
}

int glapp_check(const char *what, struct swell_err *err)
{
    GLenum e = glGetError();
    if (e == GL_NO_ERROR)
        return SWELL_OK;
    for (int i = 0; i < 16 && glGetError() != GL_NO_ERROR; i++)
        ;   /* one flag per kind: a stale one would be blamed on the next call */
    return swell_fail(err, SWELL_E_GL, "%s: GL error 0x%04x%s", what, (unsigned)e,
                      e == GL_OUT_OF_MEMORY ? " (out of memory)" : "");
}

/* SWELL_E_SHADER saying what failed with the driver's log of obj, which is deleted. */
static int log_fail(GLuint obj, int is_program, const char *what, const char *path,
                    struct swell_err *err)
{
    GLint n = 0;
    if (is_program)
        glGetProgramiv(obj, GL_INFO_LOG_LENGTH, &n);
    else
        glGetShaderiv(obj, GL_INFO_LOG_LENGTH, &n);
    char *log = calloc(1, (size_t)(n > 0 ? n : 1) + 1);
    if (log && n > 0) {
        if (is_program)
            glGetProgramInfoLog(obj, n, NULL, log);
        else
            glGetShaderInfoLog(obj, n, NULL, log);
    }
    int rc = swell_fail(err, SWELL_E_SHADER, "shader: %s %s failed: %s", what, path,
                        log && log[0] ? log : "(no log)");
    free(log);
    if (is_program)
        glDeleteProgram(obj);
    else
        glDeleteShader(obj);
    return rc;
}

/* One stage: the file read whole, the prologue before it. */
static int compile(const char *dir, const char *file, GLenum stage, GLuint *out,
                   struct swell_err *err)
{
    char path[4096];
    size_t len = 0;
    uint8_t *text = NULL;
    int rc = fs_join(path, sizeof path, dir, file, err);
    if (!rc)
        rc = fs_read_file(path, 1 << 20, &text, &len, err);
    if (rc)
        return rc;
    const char *src[2] = { stage == GL_FRAGMENT_SHADER
                               ? "#version 100\nprecision mediump float;\n#line 1\n"
                               : "#version 100\n#line 1\n", (const char *)text };
    GLuint sh = glCreateShader(stage);
    glShaderSource(sh, 2, src, NULL);
    glCompileShader(sh);
    free(text);
    GLint ok = 0;
    glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok)
        return log_fail(sh, 0, "compiling", path, err);
    *out = sh;
    return SWELL_OK;
}

int glapp_program(const char *vs_file, const char *fs_file, const char *const *attribs,
                  int swell_tier, GLuint *out, struct swell_err *err)
{
    *out = 0;
    char dir[4096];
    int rc = data_dir_find(DATADIR_SHADERS, dir, sizeof dir, err);
    if (rc)
        return rc;
    const char *labels = getenv("SWELL_SHADER_LABELS");
    int label = labels && labels[0] == '1';   /* as the library's (gl/shader.c) */
    if (label)
        fprintf(stderr, "swell-program: begin %s + %s [] tier %s\n", vs_file, fs_file,
                glapp_tier_name(swell_tier));
    GLuint vs = 0, fs = 0;
    if ((rc = compile(dir, vs_file, GL_VERTEX_SHADER, &vs, err)) ||
        (rc = compile(dir, fs_file, GL_FRAGMENT_SHADER, &fs, err))) {
        if (vs)
            glDeleteShader(vs);
        return rc;
    }
    GLuint prog = glCreateProgram();
    glAttachShader(prog, vs);
    glAttachShader(prog, fs);
    for (GLuint i = 0; attribs && attribs[i]; i++)
        glBindAttribLocation(prog, i, attribs[i]);
    glLinkProgram(prog);
    glDeleteShader(vs);
    glDeleteShader(fs);
    GLint ok = 0;
    glGetProgramiv(prog, GL_LINK_STATUS, &ok);
    if (!ok) {
        char what[4096 + 80];
        snprintf(what, sizeof what, "%s/%s + %s", dir, vs_file, fs_file);
        return log_fail(prog, 1, "linking", what, err);
    }
    if ((rc = glapp_check("shader: after linking", err))) {
        glDeleteProgram(prog);
        return rc;
    }
    if (label)
        fprintf(stderr, "swell-program: end\n");
    *out = prog;
    return SWELL_OK;
}
