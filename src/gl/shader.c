/* shader.c - GLSL ES 1.00 loader: includes, header, #line file table, compile/link logs mapped
 * back to file:line, uniform locations cached into the caller's enum-indexed array (shader.h).
 */
#include "gl/shader.h"

#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/datadir.h"
#include "core/fsutil.h"

#define PRELUDE_NAME "<swell header>"
#define MAX_NAME 128

/* Growing string; `oom` sticks so callers check once at the end. */
static void sb_printf(struct membuf *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void sb_printf(struct membuf *b, const char *fmt, ...)
{
    char tmp[512];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(tmp, sizeof tmp, fmt, ap);
    va_end(ap);
    if (n < 0)
        return;
    membuf_add(b, tmp, (size_t)n < sizeof tmp ? (size_t)n : sizeof tmp - 1);
}

/* One stage being assembled. files[0] is the generated header; the rest are source files, and
 * their index is the source-string number in `#line N F`. */
struct assembly {
    const char *dir;
    char dir_found[4096];     /* the shader directory found (core/datadir.h) when d->dir is NULL */
    struct membuf out;
    char files[SHADER_MAX_FILES][MAX_NAME];
    int nfiles;
    int stack[SHADER_MAX_INCLUDE_DEPTH + 1];   /* file indices of the include chain */
    int depth;
};

/* `#line` sets the number of the next line (Mesa 22 and glslang both do this for #version 100,
 * whatever the 1.00 text says), but Mesa drops the source-string number from its log. So the
 * file index is also encoded in the line number itself: line F * LINE_FILE_STRIDE + N. */
#define LINE_FILE_STRIDE 100000

static void emit_line(struct assembly *a, int next_line, int file)
{
    sb_printf(&a->out, "#line %d %d\n", file * LINE_FILE_STRIDE + next_line, file);
}

static int read_file(const char *dir, const char *name, char **out, struct swell_err *err)
{
    *out = NULL;
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    /* O_NONBLOCK and a regular file only: a FIFO in place of a shader must not hang (issue 17) */
    int fd = open(path, O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0)
        return swell_fail(err, SWELL_E_IO, "shader: cannot open %s: %s", path, strerror(errno));
    struct stat st;
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        close(fd);
        return swell_fail(err, SWELL_E_IO, "shader: %s is not a regular file (a FIFO, device or "
                          "directory): replace it with the shader itself", path);
    }
    FILE *f = fdopen(fd, "rb");
    if (!f) {
        close(fd);
        return swell_fail(err, SWELL_E_IO, "shader: cannot open %s: %s", path, strerror(errno));
    }
    struct membuf b = { 0 };
    char chunk[4096];
    size_t n;
    while ((n = fread(chunk, 1, sizeof chunk, f)) > 0)
        membuf_add(&b, chunk, n);
    int bad = ferror(f);
    fclose(f);
    if (bad || b.oom) {
        free(b.p);
        return swell_fail(err, bad ? SWELL_E_IO : SWELL_E_NOMEM, "shader: reading %s failed%s",
                          path, bad ? "" : ": out of memory");
    }
    if (!b.p)
        membuf_add(&b, "", 0);
    if (b.oom || memchr(b.p, '\0', b.n)) {
        free(b.p);
        return swell_fail(err, SWELL_E_FORMAT, "shader: %s is empty or has a NUL byte", path);
    }
    *out = b.p;
    return SWELL_OK;
}

static int valid_name(const char *s, size_t n)
{
    return n > 0 && n < MAX_NAME && !memchr(s, '/', n) && !memchr(s, '\\', n) &&
           !(n >= 2 && s[0] == '.' && s[1] == '.');
}

/* If `line` (length n) is an #include directive, return 1 and the quoted name span; -1 if it
 * is one but malformed; 0 otherwise. Same for #version (returns 2). */
static int directive(const char *line, size_t n, const char **name, size_t *name_len)
{
    const char *p = line, *end = line + n;
    while (p < end && (*p == ' ' || *p == '\t'))
        p++;
    if (p == end || *p != '#')
        return 0;
    p++;
    while (p < end && (*p == ' ' || *p == '\t'))
        p++;
    if ((size_t)(end - p) >= 7 && memcmp(p, "version", 7) == 0)
        return 2;
    if ((size_t)(end - p) < 7 || memcmp(p, "include", 7) != 0)
        return 0;
    p += 7;
    while (p < end && (*p == ' ' || *p == '\t'))
        p++;
    if (p == end || *p != '"')
        return -1;
    const char *q = memchr(p + 1, '"', (size_t)(end - p - 1));
    if (!q)
        return -1;
    *name = p + 1;
    *name_len = (size_t)(q - p - 1);
    for (const char *r = q + 1; r < end; r++)
        if (*r != ' ' && *r != '\t' && *r != '\r')
            return -1;
    return 1;
}

static int find_file(const struct assembly *a, const char *name, size_t n)
{
    for (int i = 1; i < a->nfiles; i++)
        if (strlen(a->files[i]) == n && memcmp(a->files[i], name, n) == 0)
            return i;
    return -1;
}

static int include_file(struct assembly *a, int file, struct swell_err *err);

static int process_line(struct assembly *a, int file, int line_no, const char *line, size_t n,
                        struct swell_err *err)
{
    const char *name = NULL;
    size_t name_len = 0;
    int kind = directive(line, n, &name, &name_len);
    const char *here = a->files[file];
    if (kind == 0) {
        membuf_add(&a->out, line, n);
        membuf_add(&a->out, "\n", 1);
        return SWELL_OK;
    }
    if (kind == 2)
        return swell_fail(err, SWELL_E_SHADER, "%s/%s:%d: remove #version: the loader prepends "
                          "#version 100 and the tier header", a->dir, here, line_no);
    if (kind < 0 || !valid_name(name, name_len))
        return swell_fail(err, SWELL_E_SHADER, "%s/%s:%d: malformed #include; write "
                          "#include \"file.glsl\" naming a file in %s", a->dir, here, line_no,
                          a->dir);
    int inc = find_file(a, name, name_len);
    if (inc >= 0) {
        for (int i = 0; i <= a->depth; i++) {
            if (a->stack[i] != inc)
                continue;
            char chain[512] = "";
            for (int j = i; j <= a->depth; j++) {
                strncat(chain, a->files[a->stack[j]], sizeof chain - strlen(chain) - 1);
                strncat(chain, " -> ", sizeof chain - strlen(chain) - 1);
            }
            strncat(chain, a->files[inc], sizeof chain - strlen(chain) - 1);
            return swell_fail(err, SWELL_E_SHADER, "%s/%s:%d: #include cycle: %s", a->dir, here,
                              line_no, chain);
        }
        /* Already inlined on another branch: once is enough (include-once semantics). */
        membuf_add(&a->out, "\n", 1);
        return SWELL_OK;
    }
    if (a->depth + 1 > SHADER_MAX_INCLUDE_DEPTH)
        return swell_fail(err, SWELL_E_SHADER, "%s/%s:%d: #include nested deeper than %d",
                          a->dir, here, line_no, SHADER_MAX_INCLUDE_DEPTH);
    if (a->nfiles >= SHADER_MAX_FILES)
        return swell_fail(err, SWELL_E_SHADER, "%s/%s:%d: more than %d files in one stage",
                          a->dir, here, line_no, SHADER_MAX_FILES);
    inc = a->nfiles++;
    memcpy(a->files[inc], name, name_len);
    a->files[inc][name_len] = '\0';
    a->stack[++a->depth] = inc;
    int rc = include_file(a, inc, err);
    a->depth--;
    if (rc == SWELL_E_IO)
        return swell_err_context(err, "%s/%s:%d: #include", a->dir, here, line_no);
    if (rc)
        return rc;
    emit_line(a, line_no + 1, file);
    return SWELL_OK;
}

static int include_file(struct assembly *a, int file, struct swell_err *err)
{
    char *text = NULL;
    int rc = read_file(a->dir, a->files[file], &text, err);
    if (rc)
        return rc;
    emit_line(a, 1, file);
    int line_no = 1;
    const char *p = text;
    while (*p) {
        const char *nl = strchr(p, '\n');
        size_t n = nl ? (size_t)(nl - p) : strlen(p);
        if (line_no >= LINE_FILE_STRIDE) {
            rc = swell_fail(err, SWELL_E_SHADER, "%s/%s: more than %d lines", a->dir,
                            a->files[file], LINE_FILE_STRIDE - 1);
            break;
        }
        rc = process_line(a, file, line_no, p, n, err);
        if (rc)
            break;
        line_no++;
        p += n + (nl ? 1 : 0);
    }
    free(text);
    return rc;
}

static int valid_ident(const char *s, size_t n)
{
    if (n == 0 || !(isalpha((unsigned char)s[0]) || s[0] == '_'))
        return 0;
    for (size_t i = 1; i < n; i++)
        if (!(isalnum((unsigned char)s[i]) || s[i] == '_'))
            return 0;
    return 1;
}

/* Caller defines -> #define lines; sets *want_highp when SWELL_HIGHP is among them. */
static int emit_defines(struct membuf *b, const char *defines, int *want_highp,
                        struct swell_err *err)
{
    *want_highp = 0;
    const char *p = defines ? defines : "";
    while (*p) {
        while (*p && isspace((unsigned char)*p))
            p++;
        if (!*p)
            break;
        const char *start = p;
        while (*p && !isspace((unsigned char)*p))
            p++;
        size_t n = (size_t)(p - start);
        const char *eq = memchr(start, '=', n);
        size_t name_n = eq ? (size_t)(eq - start) : n;
        if (!valid_ident(start, name_n) || (eq && eq + 1 == p))
            return swell_fail(err, SWELL_E_ARG, "shader: define '%.*s' is not NAME or NAME=VALUE",
                              (int)n, start);
        if (name_n == 11 && memcmp(start, "SWELL_HIGHP", 11) == 0)
            *want_highp = 1;
        if (eq)
            sb_printf(b, "#define %.*s %.*s\n", (int)name_n, start, (int)(p - eq - 1), eq + 1);
        else
            sb_printf(b, "#define %.*s 1\n", (int)name_n, start);
    }
    return SWELL_OK;
}

static const char *const tier_macros[TIER_COUNT] = {
    "SWELL_TIER_GLES2_MIN", "SWELL_TIER_GLES2_EXT", "SWELL_TIER_GLES3"
};

int shader_is_es3(const struct gpu_caps *c)
{
    return c->tier == TIER_GLES3 && c->glsl300;
}

int shader_has_gradients(const struct gpu_caps *c)
{
    return shader_is_es3(c) ||
           (c->glsl100_texture_lod && c->texture_lod && c->glsl100_derivatives && c->derivatives);
}

static int emit_header(struct assembly *a, const struct shader_desc *d, GLenum stage,
                       struct swell_err *err)
{
    const struct gpu_caps *c = d->caps;
    int fragment = stage == GL_FRAGMENT_SHADER;
    struct membuf *b = &a->out;
    int tier = c->tier >= 0 && c->tier < TIER_COUNT ? c->tier : TIER_GLES2_MIN;
    /* The gles3 tier compiles the same sources as GLSL ES 3.00, through the GLSL ES 1.00 names
     * mapped onto 3.00's (as WebGL 2 ports do): derivatives and textureGrad are core there,
     * while GLES 3 drivers need not offer the 1.00 extensions (llvmpipe does not). */
    int es3 = shader_is_es3(c);
    if (es3) {
        sb_printf(b, "#version 300 es\n#define texture2D texture\n#define texture2DLod textureLod\n"
                     "#define texture2DGradEXT textureGrad\n#define texture2DLodEXT textureLod\n");
        if (fragment)
            sb_printf(b, "#define varying in\nout highp vec4 swell_frag_colour;\n"
                         "#define gl_FragColor swell_frag_colour\n");
        else
            sb_printf(b, "#define attribute in\n#define varying out\n");
    } else {
        membuf_add(b, "#version 100\n", 13);
    }
    /* GLSL ES 1.00 §3.4: #extension before any non-preprocessor token, so before precision. */
    if (!es3 && fragment && c->glsl100_derivatives && c->derivatives)
        sb_printf(b, "#extension GL_OES_standard_derivatives : enable\n");
    if (!es3 && fragment && c->glsl100_texture_lod && c->texture_lod)
        sb_printf(b, "#extension GL_EXT_shader_texture_lod : enable\n");
    sb_printf(b, "#define %s 1\n", tier_macros[tier]);
    if (fragment ? (es3 || (c->glsl100_derivatives && c->derivatives)) : 0)
        sb_printf(b, "#define SWELL_HAS_DERIVATIVES 1\n");
    if (fragment && gpu_fragment_texture_lod(c))
        sb_printf(b, "#define SWELL_HAS_TEXTURE_LOD 1\n");
    if (c->vertex_texture_units > 0)
        sb_printf(b, "#define SWELL_HAS_VTF 1\n");
    sb_printf(b, "#define %s 1\n", fragment ? "SWELL_FRAGMENT_SHADER" : "SWELL_VERTEX_SHADER");
    int want_highp = 0;
    int rc = emit_defines(b, d->defines, &want_highp, err);
    if (rc)
        return rc;
    if (fragment) {
        /* DESIGN.md: mediump only on gles2-min; highp where asked for (or preferred by the
         * device, gpu.c) and really present. */
        if ((want_highp || c->prefer_highp) && c->fragment_highp && tier != TIER_GLES2_MIN)
            sb_printf(b, "#define SWELL_HAS_HIGHP 1\nprecision highp float;\n");
        else
            sb_printf(b, "precision mediump float;\n");
    }
    return SWELL_OK;
}

/* Fill `a` (zeroed by the caller) with the stage's source and file table. */
static int assemble(const struct shader_desc *d, GLenum stage, struct assembly *a,
                    struct swell_err *err)
{
    const char *file = stage == GL_VERTEX_SHADER ? d->vs_file : d->fs_file;
    if (!d->caps || !file || !valid_name(file, strlen(file)))
        return swell_fail(err, SWELL_E_ARG, "shader: the descriptor needs caps and plain file "
                          "names for both stages (got %s)", file ? file : "NULL");
    a->dir = d->dir;
    if (!a->dir) {
        if (data_dir_find(DATADIR_SHADERS, a->dir_found, sizeof a->dir_found, err))
            return swell_err_context(err, "shader: %s", file);
        a->dir = a->dir_found;
    }
    snprintf(a->files[0], MAX_NAME, "%s", PRELUDE_NAME);
    snprintf(a->files[1], MAX_NAME, "%s", file);
    a->nfiles = 2;
    a->stack[0] = 1;
    int rc = emit_header(a, d, stage, err);
    if (!rc)
        rc = include_file(a, 1, err);
    if (!rc && a->out.oom)
        rc = swell_fail(err, SWELL_E_NOMEM, "shader: no memory to assemble %s", file);
    return rc;
}

int shader_assemble(const struct shader_desc *d, GLenum stage, char **source,
                    struct swell_err *err)
{
    *source = NULL;
    struct assembly *a = calloc(1, sizeof *a);
    if (!a)
        return swell_fail(err, SWELL_E_NOMEM, "shader: no memory to assemble a stage");
    int rc = assemble(d, stage, a, err);
    if (rc)
        free(a->out.p);
    else
        *source = a->out.p;
    free(a);
    return rc;
}

/* Rewrite driver log lines "S:L(C): msg" (Mesa) or "ERROR: S:L: msg" (others) as
 * "dir/file:L: msg" using the source-string table. Unrecognised lines are kept. */
static void map_log(const struct assembly *a, const char *log, struct membuf *out)
{
    const char *p = log;
    while (*p) {
        const char *nl = strchr(p, '\n');
        size_t n = nl ? (size_t)(nl - p) : strlen(p);
        const char *q = p, *end = p + n;
        const char *severity = "";
        if (n >= 7 && memcmp(q, "ERROR: ", 7) == 0) {
            severity = "error: ";
            q += 7;
        } else if (n >= 9 && memcmp(q, "WARNING: ", 9) == 0) {
            severity = "warning: ";
            q += 9;
        }
        char *e1 = NULL, *e2 = NULL;
        long src = strtol(q, &e1, 10);
        long line = 0;
        int ok = e1 && e1 > q && e1 < end && *e1 == ':' && isdigit((unsigned char)e1[1]);
        if (ok) {
            line = strtol(e1 + 1, &e2, 10);
            ok = e2 <= end && src >= 0 && line >= 0;
        }
        if (ok) {
            /* Source string from the line number (see emit_line); the log's own may be 0. */
            src = line / LINE_FILE_STRIDE;
            line %= LINE_FILE_STRIDE;
            ok = src < a->nfiles;
        }
        if (ok) {
            const char *rest = e2;
            if (rest < end && *rest == '(') {
                const char *close = memchr(rest, ')', (size_t)(end - rest));
                if (close)
                    rest = close + 1;
            }
            while (rest < end && (*rest == ':' || *rest == ' '))
                rest++;
            if (src == 0)
                sb_printf(out, "%s:%ld: ", a->files[0], line);
            else
                sb_printf(out, "%s/%s:%ld: ", a->dir, a->files[src], line);
            membuf_add(out, severity, strlen(severity));
            membuf_add(out, rest, (size_t)(end - rest));
        } else {
            membuf_add(out, p, n);
        }
        if (n)
            membuf_add(out, "\n", 1);
        p += n + (nl ? 1 : 0);
    }
}

int shader_map_log(const struct shader_desc *d, GLenum stage, const char *log, char **mapped,
                   struct swell_err *err)
{
    *mapped = NULL;
    struct assembly *a = calloc(1, sizeof *a);
    if (!a)
        return swell_fail(err, SWELL_E_NOMEM, "shader: no memory to assemble a stage");
    int rc = assemble(d, stage, a, err);
    struct membuf out = { 0 };
    if (!rc) {
        map_log(a, log, &out);
        if (out.oom)
            rc = swell_fail(err, SWELL_E_NOMEM, "shader: no memory to map a log");
    }
    free(a->out.p);
    free(a);
    if (!rc && !out.p && !(out.p = calloc(1, 1)))
        rc = swell_fail(err, SWELL_E_NOMEM, "shader: no memory to map a log");
    if (rc)
        free(out.p);
    else
        *mapped = out.p;
    return rc;
}

/* The driver's log for a shader (is_program 0) or program (1); malloc'd or NULL. */
static char *gl_log(GLuint obj, int is_program)
{
    GLint len = 0;
    if (is_program)
        glGetProgramiv(obj, GL_INFO_LOG_LENGTH, &len);
    else
        glGetShaderiv(obj, GL_INFO_LOG_LENGTH, &len);
    char *log = malloc((size_t)(len > 1 ? len : 1) + 1);
    if (!log)
        return NULL;
    log[0] = '\0';
    if (len > 1) {
        if (is_program)
            glGetProgramInfoLog(obj, len, NULL, log);
        else
            glGetShaderInfoLog(obj, len, NULL, log);
    }
    return log;
}

static int compile_stage(const struct shader_desc *d, GLenum stage, GLuint *shader,
                         struct swell_err *err)
{
    *shader = 0;
    const char *what = stage == GL_VERTEX_SHADER ? "vertex" : "fragment";
    struct assembly *a = calloc(1, sizeof *a);
    if (!a)
        return swell_fail(err, SWELL_E_NOMEM, "shader: no memory for the %s stage", what);
    int rc = assemble(d, stage, a, err);
    if (rc)
        goto done;
    *shader = glCreateShader(stage);
    if (!*shader) {
        rc = swell_fail(err, SWELL_E_GL, "shader: glCreateShader(%s) failed for %s/%s", what,
                        a->dir, a->files[1]);
        goto done;
    }
    const GLchar *strings[1] = { a->out.p };
    glShaderSource(*shader, 1, strings, NULL);
    glCompileShader(*shader);
    GLint ok = 0;
    glGetShaderiv(*shader, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char *log = gl_log(*shader, 0);
        struct membuf mapped = { 0 };
        map_log(a, log ? log : "(no log)", &mapped);
        rc = swell_fail(err, SWELL_E_SHADER, "%s(%s shader, tier %s; tools/validate-shaders.sh "
                        "checks every tier)", mapped.p ? mapped.p : "(no log)\n", what,
                        gpu_tier_name(d->caps->tier));
        free(mapped.p);
        free(log);
        glDeleteShader(*shader);
        *shader = 0;
    }
done:
    free(a->out.p);
    free(a);
    return rc;
}

int shader_program_build(const struct shader_desc *d, struct shader_program *out,
                         struct swell_err *err)
{
    out->program = 0;
    GLuint vs = 0, fs = 0, prog = 0;
    struct shader_desc found;
    char dir[4096];
    if (!d->dir) {      /* found once here, not once per stage (core/datadir.h) */
        if (data_dir_find(DATADIR_SHADERS, dir, sizeof dir, err))
            return swell_err_context(err, "shader: %s + %s", d->vs_file ? d->vs_file : "?",
                                     d->fs_file ? d->fs_file : "?");
        found = *d;
        found.dir = dir;
        d = &found;
    }
    if (d->uniform_count < 0 || (d->uniform_count > 0 && (!d->uniform_names ||
                                                          !d->uniform_locations)) ||
        d->attrib_count < 0 || (d->attrib_count > 0 && !d->attribs))
        return swell_fail(err, SWELL_E_ARG, "shader: uniform/attribute tables missing for %s + %s",
                          d->vs_file ? d->vs_file : "?", d->fs_file ? d->fs_file : "?");
    /* SWELL_SHADER_LABELS: each build between two labelled lines on stderr, so what a driver
     * prints while compiling and linking it (its statistics, tools/devices.py) can be told
     * apart by program */
    if (shader_labels())
        fprintf(stderr, "swell-program: begin %s + %s [%s] tier %s\n", d->vs_file, d->fs_file,
                d->defines ? d->defines : "", gpu_tier_name(d->caps->tier));
    int rc = compile_stage(d, GL_VERTEX_SHADER, &vs, err);
    if (rc)
        goto fail;
    rc = compile_stage(d, GL_FRAGMENT_SHADER, &fs, err);
    if (rc)
        goto fail;
    prog = glCreateProgram();
    if (!prog) {
        rc = swell_fail(err, SWELL_E_GL, "shader: glCreateProgram failed");
        goto fail;
    }
    glAttachShader(prog, vs);
    glAttachShader(prog, fs);
    for (int i = 0; i < d->attrib_count; i++)
        glBindAttribLocation(prog, d->attribs[i].index, d->attribs[i].name);
    glLinkProgram(prog);
    GLint ok = 0;
    glGetProgramiv(prog, GL_LINK_STATUS, &ok);
    if (!ok) {
        char *log = gl_log(prog, 1);
        rc = swell_fail(err, SWELL_E_SHADER, "shader: linking %s/%s + %s (tier %s) failed: %s",
                        d->dir, d->vs_file, d->fs_file,
                        gpu_tier_name(d->caps->tier), log && log[0] ? log : "(no log)");
        free(log);
        goto fail;
    }
    /* The program keeps its code; the shader objects are no longer needed. */
    glDetachShader(prog, vs);
    glDetachShader(prog, fs);
    glDeleteShader(vs);
    glDeleteShader(fs);
    for (int i = 0; i < d->uniform_count; i++)
        d->uniform_locations[i] = glGetUniformLocation(prog, d->uniform_names[i]);
    rc = gpu_check("shader: after linking", err);
    if (rc) {
        vs = fs = 0;
        goto fail;
    }
    out->program = prog;
    if (shader_labels())
        fprintf(stderr, "swell-program: end\n");
    return SWELL_OK;

fail:
    if (prog)
        glDeleteProgram(prog);
    if (fs)
        glDeleteShader(fs);
    if (vs)
        glDeleteShader(vs);
    return rc;
}

void shader_program_destroy(struct shader_program *p)
{
    if (!p || !p->program)
        return;
    glDeleteProgram(p->program);
    p->program = 0;
}

int shader_labels(void)
{
    const char *labels = getenv("SWELL_SHADER_LABELS");
    return labels && labels[0] == '1';
}
