/* bench.c - frame timing, percentiles, the baseline quad, the instruction counter, JSON (bench.h).
 */
#include <errno.h>
#include <stdarg.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>
#include <sys/ioctl.h>
#include <sys/syscall.h>
#include <linux/perf_event.h>

#include "app/bench.h"
#include "app/glapp.h"
#include "core/fsutil.h"

#define JSON_MAX 8192

/* ---- statistics ---------------------------------------------------------------------------- */

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double bench_percentile(const double *sorted, int n, double p)
{
    if (n <= 0)
        return 0.0;
    /* Nearest rank: the smallest value with at least p n values at or below it. The small
     * tolerance keeps p n that is an integer in exact arithmetic (0.95 * 100) from rounding up. */
    double rank = ceil(p * (double)n - 1e-9);
    int k = rank < 1.0 ? 1 : rank > (double)n ? n : (int)rank;
    return sorted[k - 1];
}

void bench_stats_compute(double *ms, int n, struct bench_stats *out)
{
    memset(out, 0, sizeof *out);
    if (n <= 0)
        return;
    qsort(ms, (size_t)n, sizeof ms[0], cmp_double);
    double sum = 0.0;
    for (int i = 0; i < n; i++)
        sum += ms[i];
    out->n = n;
    out->median_ms = n % 2 ? ms[n / 2] : 0.5 * (ms[n / 2 - 1] + ms[n / 2]);
    out->p95_ms = bench_percentile(ms, n, 0.95);
    out->mean_ms = sum / n;
    out->min_ms = ms[0];
    out->max_ms = ms[n - 1];
}

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return 1e3 * (double)ts.tv_sec + 1e-6 * (double)ts.tv_nsec;
}

/* ---- instruction counter ------------------------------------------------------------------- */

int bench_counter_open(struct bench_counter *c)
{
    struct perf_event_attr a;
    memset(c, 0, sizeof *c);
    memset(&a, 0, sizeof a);
    a.type = PERF_TYPE_HARDWARE;
    a.size = sizeof a;
    a.config = PERF_COUNT_HW_INSTRUCTIONS;
    a.disabled = 1;
    a.exclude_kernel = 1;
    a.exclude_hv = 1;
    /* pid 0, cpu -1: this thread on any CPU; Mesa's rasterizer threads are not counted. */
    c->fd = (int)syscall(SYS_perf_event_open, &a, 0, -1, -1, 0);
    if (c->fd >= 0)
        return 1;
    int e = errno;
    snprintf(c->why, sizeof c->why, "perf_event_open(PERF_COUNT_HW_INSTRUCTIONS, user space, "
             "this thread) failed: %s%s", strerror(e),
             e == ENOENT || e == EOPNOTSUPP ? " (no hardware PMU exposed here, e.g. a virtual "
             "machine without PMU passthrough); tools/bench.sh measures with callgrind instead"
             : e == EACCES || e == EPERM ? " (kernel.perf_event_paranoid forbids it; lower it "
             "or run tools/bench.sh, which measures with callgrind)" : "");
    c->fd = -1;
    return 0;
}

void bench_counter_start(struct bench_counter *c)
{
    if (c->fd < 0)
        return;
    ioctl(c->fd, PERF_EVENT_IOC_RESET, 0);
    ioctl(c->fd, PERF_EVENT_IOC_ENABLE, 0);
}

uint64_t bench_counter_stop(struct bench_counter *c)
{
    uint64_t v = 0;
    if (c->fd < 0)
        return 0;
    ioctl(c->fd, PERF_EVENT_IOC_DISABLE, 0);
    if (read(c->fd, &v, sizeof v) != (ssize_t)sizeof v)
        return 0;
    return v;
}

void bench_counter_close(struct bench_counter *c)
{
    if (c->fd > 0)
        close(c->fd);
    c->fd = -1;
}

/* ---- the baseline quad --------------------------------------------------------------------- */

enum { QU_TEX = 0, QU_UV_SCALE, QU_COUNT };
static const char *const quad_uniform_names[QU_COUNT] = { "quad_tex", "uv_scale" };

struct quad {
    GLuint prog;
    GLint u[QU_COUNT];
    GLuint tex, vbo;
};

static void quad_destroy(struct quad *q)
{
    if (q->vbo)
        glDeleteBuffers(1, &q->vbo);
    if (q->tex)
        glDeleteTextures(1, &q->tex);
    if (q->prog)
        glDeleteProgram(q->prog);
    memset(q, 0, sizeof *q);
}

/* Deterministic noise (an integer hash) so the texture cache sees real content, not one colour. */
static uint32_t hash32(uint32_t x)
{
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

static int quad_create(struct quad *q, int swell_tier, struct swell_err *err)
{
    static const float ndc[8] = { -1, -1, 1, -1, -1, 1, 1, 1 };
    static const char *const attribs[] = { "a_ndc", NULL };
    const int n = BENCH_QUAD_SIZE;
    memset(q, 0, sizeof *q);
    int rc = glapp_program("bench_quad.vert", "bench_quad.frag", attribs, swell_tier, &q->prog,
                           err);
    if (rc)
        goto fail;
    for (int i = 0; i < QU_COUNT; i++)
        q->u[i] = glGetUniformLocation(q->prog, quad_uniform_names[i]);
    uint32_t *texels = malloc((size_t)n * (size_t)n * sizeof *texels);
    if (!texels) {
        rc = swell_fail(err, SWELL_E_NOMEM, "bench: no memory for the %dx%d baseline texture",
                        n, n);
        goto fail;
    }
    for (int i = 0; i < n * n; i++)
        texels[i] = hash32((uint32_t)i) | 0xff000000u;
    /* RGBA8, mipmapped, trilinear, repeating; never anisotropic (notes/llvmpipe.md) */
    glActiveTexture(GL_TEXTURE0);
    glGenTextures(1, &q->tex);
    glBindTexture(GL_TEXTURE_2D, q->tex);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, n, n, 0, GL_RGBA, GL_UNSIGNED_BYTE, texels);
    glGenerateMipmap(GL_TEXTURE_2D);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_REPEAT);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_REPEAT);
    free(texels);
    glGenBuffers(1, &q->vbo);
    glBindBuffer(GL_ARRAY_BUFFER, q->vbo);
    glBufferData(GL_ARRAY_BUFFER, sizeof ndc, ndc, GL_STATIC_DRAW);
    rc = glapp_check("bench: baseline upload", err);
    if (rc)
        goto fail;
    return SWELL_OK;

fail:
    quad_destroy(q);
    return rc;
}

static int quad_draw(struct quad *q, int w, int h, struct swell_err *err)
{
    /* Texel density 1.41 per pixel on both axes: LOD ~0.5, so every fetch really blends two mip
     * levels (trilinear), isotropic, at any frame size. */
    const float density = 1.41421356f;
    glViewport(0, 0, w, h);
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glUseProgram(q->prog);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, q->tex);
    glUniform1i(q->u[QU_TEX], 0);
    glUniform2f(q->u[QU_UV_SCALE], density * (float)w / BENCH_QUAD_SIZE,
                density * (float)h / BENCH_QUAD_SIZE);
    glBindBuffer(GL_ARRAY_BUFFER, q->vbo);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, (const void *)0);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    glDisableVertexAttribArray(0);
    return glapp_check("bench: baseline quad", err);
}

/* ---- the run ------------------------------------------------------------------------------- */

static void copy_label(char *dst, size_t cap, const char *src)
{
    snprintf(dst, cap, "%s", src ? src : "");
}

/* One whole frame: bind the target, draw, present, glFinish (so the GPU work is inside the
 * time even where present only flushes). Returns ms; *instr gets the counted instructions of
 * the frame callback when a counter is given. */
static int scene_frame(const struct bench_desc *d, struct bench_counter *c, double t, int w,
                       int h, double *ms, uint64_t *instr, struct swell_err *err)
{
    struct camera cam = d->camera;
    if (d->path > CAMERA_PATH_NONE)
        camera_path_at(d->path, t, &cam);
    double t0 = now_ms();
    int rc = d->ph->be->begin_frame(d->ph->p, err);
    if (!rc) {
        if (c)
            bench_counter_start(c);
        rc = d->frame(d->ctx, &cam, t, err);
        if (c)
            *instr = bench_counter_stop(c);
    }
    if (!rc)
        rc = d->ph->be->present(d->ph->p, err);
    glFinish();
    *ms = now_ms() - t0;
    return rc;
}

static int quad_frame(const struct bench_desc *d, struct quad *q, int w, int h, double *ms,
                      struct swell_err *err)
{
    double t0 = now_ms();
    int rc = d->ph->be->begin_frame(d->ph->p, err);
    if (!rc)
        rc = quad_draw(q, w, h, err);
    if (!rc)
        rc = d->ph->be->present(d->ph->p, err);
    glFinish();
    *ms = now_ms() - t0;
    return rc;
}

int bench_run(const struct bench_desc *d, struct bench_result *out, struct swell_err *err)
{
    memset(out, 0, sizeof *out);
    int frames = d->frames > 0 ? d->frames : BENCH_DEFAULT_FRAMES;
    int warmup = d->warmup > 0 ? d->warmup : d->warmup < 0 ? 0 : BENCH_DEFAULT_WARMUP;
    double step = d->step_s > 0 ? d->step_s : 1.0 / 30.0;
    int w = 0, h = 0;
    d->ph->be->size(d->ph->p, &w, &h);

    struct quad q;
    struct bench_counter ctr;
    memset(&q, 0, sizeof q);
    bench_counter_open(&ctr);
    double *scene_ms = calloc((size_t)frames, sizeof *scene_ms);
    double *quad_ms = calloc((size_t)frames, sizeof *quad_ms);
    int rc = SWELL_OK;
    if (!scene_ms || !quad_ms) {
        rc = swell_fail(err, SWELL_E_NOMEM, "bench: no memory for %d frame times", frames);
        goto done;
    }
    rc = quad_create(&q, d->swell_tier, err);
    if (rc)
        goto done;

    double t = d->time0_s, ms;
    uint64_t instr = 0, instr_sum = 0;
    for (int i = 0; i < warmup && !rc; i++, t += step) {
        rc = scene_frame(d, NULL, t, w, h, &ms, &instr, err);
        if (!rc)
            rc = quad_frame(d, &q, w, h, &ms, err);
    }
    for (int i = 0; i < frames && !rc; i++, t += step) {
        rc = scene_frame(d, &ctr, t, w, h, &scene_ms[i], &instr, err);
        instr_sum += instr;
        if (!rc)
            rc = quad_frame(d, &q, w, h, &quad_ms[i], err);
    }
    if (rc) {
        swell_err_context(err, "bench: frame at t = %.3f s", t);
        goto done;
    }

    bench_stats_compute(scene_ms, frames, &out->frame);
    bench_stats_compute(quad_ms, frames, &out->quad);
    out->ratio = out->quad.median_ms > 0 ? out->frame.median_ms / out->quad.median_ms : 0.0;
    out->width = w;
    out->height = h;
    out->scale = d->scale > 0 ? d->scale : 1.0;
    out->warmup = warmup;
    out->frames = frames;
    out->step_s = step;
    copy_label(out->scene, sizeof out->scene, d->scene);
    copy_label(out->quality, sizeof out->quality, d->quality);
    copy_label(out->geometry, sizeof out->geometry, d->geometry);
    copy_label(out->detile, sizeof out->detile, d->detile ? d->detile : "on");
    copy_label(out->platform, sizeof out->platform, d->platform ? d->platform : d->ph->be->name);
    copy_label(out->tier, sizeof out->tier, glapp_tier_name(d->swell_tier));
    copy_label(out->path, sizeof out->path,
               d->path > CAMERA_PATH_NONE ? camera_path_name(d->path) : "fixed");
    copy_label(out->gl_renderer, sizeof out->gl_renderer,
               (const char *)glGetString(GL_RENDERER));

    out->cpu_scope = d->cpu_scope ? d->cpu_scope : "the scene's frame on the calling thread";
    if (ctr.fd >= 0) {
        out->cpu_valid = 1;
        out->cpu_instructions_per_frame = (double)instr_sum / frames;
        snprintf(out->notes, sizeof out->notes, "scene and baseline frames interleaved; "
                 "each frame ends with glFinish");
    } else {
        snprintf(out->notes, sizeof out->notes, "cpu_instructions_per_frame: %s", ctr.why);
    }

done:
    quad_destroy(&q);
    free(quad_ms);
    free(scene_ms);
    bench_counter_close(&ctr);
    return rc;
}

/* ---- output -------------------------------------------------------------------------------- */

struct jbuf {
    char *p;
    size_t cap, len;    /* len counts what would have been written, like snprintf */
};

static void jput(struct jbuf *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void jput(struct jbuf *b, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    size_t room = b->len < b->cap ? b->cap - b->len : 0;
    int n = vsnprintf(room ? b->p + b->len : NULL, room, fmt, ap);
    va_end(ap);
    if (n > 0)
        b->len += (size_t)n;
}

/* A JSON string: quotes, backslashes and control characters escaped (RFC 8259 §7). */
static void jstr(struct jbuf *b, const char *key, const char *s)
{
    jput(b, "  \"%s\": \"", key);
    for (const unsigned char *c = (const unsigned char *)(s ? s : ""); *c; c++) {
        if (*c == '"' || *c == '\\')
            jput(b, "\\%c", *c);
        else if (*c < 0x20)
            jput(b, "\\u%04x", *c);
        else
            jput(b, "%c", *c);
    }
    jput(b, "\",\n");
}

/* A number; NaN and infinities have no JSON spelling and become null. */
static void jnum(struct jbuf *b, const char *key, double v, int valid)
{
    if (valid && isfinite(v))
        jput(b, "  \"%s\": %.6g,\n", key, v);
    else
        jput(b, "  \"%s\": null,\n", key);
}

int bench_format_json(const struct bench_result *r, char *buf, size_t cap)
{
    struct jbuf b = { buf, cap, 0 };
    if (cap)
        buf[0] = '\0';
    jput(&b, "{\n");
    jstr(&b, "scene", r->scene);
    jstr(&b, "tier", r->tier);
    jstr(&b, "quality", r->quality);
    jstr(&b, "geometry", r->geometry);
    jstr(&b, "detile", r->detile);
    jstr(&b, "path", r->path);
    jstr(&b, "platform", r->platform);
    jstr(&b, "gl_renderer", r->gl_renderer);
    jput(&b, "  \"size\": \"%dx%d\",\n  \"width\": %d,\n  \"height\": %d,\n", r->width,
         r->height, r->width, r->height);
    jnum(&b, "scale", r->scale, 1);
    jput(&b, "  \"warmup_frames\": %d,\n  \"frames\": %d,\n", r->warmup, r->frames);
    jnum(&b, "step_s", r->step_s, 1);
    jnum(&b, "ms_median", r->frame.median_ms, r->frame.n > 0);
    jnum(&b, "ms_p95", r->frame.p95_ms, r->frame.n > 0);
    jnum(&b, "ms_mean", r->frame.mean_ms, r->frame.n > 0);
    jnum(&b, "ms_min", r->frame.min_ms, r->frame.n > 0);
    jnum(&b, "ms_max", r->frame.max_ms, r->frame.n > 0);
    jnum(&b, "baseline_quad_ms", r->quad.median_ms, r->quad.n > 0);
    jnum(&b, "baseline_quad_ms_p95", r->quad.p95_ms, r->quad.n > 0);
    jnum(&b, "ratio", r->ratio, r->quad.n > 0 && r->quad.median_ms > 0);
    jnum(&b, "cpu_instructions_per_frame", r->cpu_instructions_per_frame, r->cpu_valid);
    jstr(&b, "cpu_instructions_scope", r->cpu_scope);
    jput(&b, "  \"bytes_gpu\": %llu,\n  \"budget_bytes\": %llu,\n",
         (unsigned long long)r->bytes_gpu, (unsigned long long)r->budget_bytes);
    jput(&b, "  \"bytes_streamed_per_frame\": %llu,\n  \"vertices\": %d,\n  \"triangles\": %d,\n",
         (unsigned long long)r->bytes_streamed_per_frame, r->vertices, r->triangles);
    jstr(&b, "notes", r->notes);
    /* the last member, so every member above can end with a comma */
    jput(&b, "  \"generator\": \"swell --bench\"\n}");
    return b.len > (size_t)0x7fffffff ? 0x7fffffff : (int)b.len;
}

int bench_write_json(const char *path, const struct bench_result *r, struct swell_err *err)
{
    char *buf = malloc(JSON_MAX);
    if (!buf)
        return swell_fail(err, SWELL_E_NOMEM, "bench: no memory to format %s", path);
    int n = bench_format_json(r, buf, JSON_MAX - 1);
    int rc;
    if (n < 0 || n >= JSON_MAX - 2) {
        rc = swell_fail(err, SWELL_E_ARG, "bench: the result for %s needs %d bytes, more than "
                        "the %d reserved", path, n, JSON_MAX);
    } else {
        buf[n] = '\n';
        rc = fs_write_atomic(path, buf, (size_t)n + 1, err);
        if (rc)
            swell_err_context(err, "writing --results %s", path);
    }
    free(buf);
    return rc;
}

void bench_format_summary(const struct bench_result *r, char *buf, size_t cap)
{
    char cpu[48];
    if (r->cpu_valid)
        snprintf(cpu, sizeof cpu, "%.2f M instr/frame", r->cpu_instructions_per_frame / 1e6);
    else
        snprintf(cpu, sizeof cpu, "CPU instr n/a");
    char scale[32] = "";
    if (r->scale > 0 && r->scale < 1)
        snprintf(scale, sizeof scale, " scale %.2f", r->scale);
    snprintf(buf, cap, "bench: %s %s %s %s %dx%d%s: median %.2f ms, p95 %.2f ms over %d frames; "
             "quad %.2f ms; ratio %.2f; %s; GPU %.2f MiB",
             r->scene[0] ? r->scene : "-", r->path, r->tier, r->quality, r->width, r->height,
             scale, r->frame.median_ms, r->frame.p95_ms, r->frames, r->quad.median_ms, r->ratio, cpu,
             r->bytes_gpu / 1048576.0);
}
