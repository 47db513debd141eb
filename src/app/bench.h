/* bench.h - `swell --bench`: frame-time percentiles beside a baseline measured in the same run
 * (issue 5 "Benchmarks", glmark2-style), CPU instructions per frame, results as JSON.
 *
 * Method (../shared/notes/llvmpipe.md): every timed frame is a whole frame, begin_frame ->
 * the application's frame (bench_desc frame) -> present -> glFinish, timed on CLOCK_MONOTONIC;
 * the baseline is one fullscreen quad sampling a 512x512 RGBA8 mipmapped texture, trilinear,
 * one draw per glFinish, timed the same way on the same platform, size and context. Scene and baseline frames are
 * interleaved (scene i, quad i, scene i+1, ...) so load from other processes hits both alike
 * and the ratio stays meaningful on a shared machine. Anisotropic filtering is never enabled.
 */
#ifndef SWELL_BENCH_H
#define SWELL_BENCH_H

#include <stddef.h>
#include <stdint.h>
#include "core/camera.h"
#include "core/err.h"
#include "platform/platform.h"

#define BENCH_DEFAULT_FRAMES 100    /* timed frames (issue 5: >= 100 after warm-up) */
#define BENCH_DEFAULT_WARMUP 10
#define BENCH_QUAD_SIZE 512         /* baseline texture side, texels */

/* Order statistics of a sample of frame times, ms. */
struct bench_stats {
    int n;
    double median_ms;           /* middle value; mean of the two middle values when n is even */
    double p95_ms;              /* nearest rank: the ceil(0.95 n)-th smallest value */
    double mean_ms, min_ms, max_ms;
};

/* Sorts ms[0..n) ascending in place and fills out (all zero when n <= 0). */
void bench_stats_compute(double *ms, int n, struct bench_stats *out);
/* Nearest-rank percentile of an ascending sample: the ceil(p n)-th smallest, p in (0, 1]. */
double bench_percentile(const double *sorted, int n, double p);

/* User-space instructions retired by the calling thread (perf_event_open,
 * PERF_COUNT_HW_INSTRUCTIONS, exclude_kernel). fd -1 when the kernel refuses; why says so. */
struct bench_counter {
    int fd;
    char why[256];
};

/* Returns 1 when the counter works, 0 (with c->why filled) when it does not; never fails. */
int  bench_counter_open(struct bench_counter *c);
void bench_counter_start(struct bench_counter *c);
uint64_t bench_counter_stop(struct bench_counter *c);   /* instructions since start */
void bench_counter_close(struct bench_counter *c);      /* accepts a zeroed or closed counter */

struct bench_desc {
    struct platform_handle *ph;     /* not owned */
    /* One frame of the scene into the platform's framebuffer (the app's: sea and objects,
     * through swell.h; swell.c), with the camera of this frame */
    int (*frame)(void *ctx, const struct camera *cam, double t, struct swell_err *err);
    void *ctx;
    struct camera camera;           /* used when path is CAMERA_PATH_NONE */
    int path;                       /* enum camera_path */
    double time0_s;                 /* animation time of the first warm-up frame, s */
    double step_s;                  /* animation step per frame, s; default 0 = 1/30 */
    int warmup;                     /* untimed frames first; default 0 = BENCH_DEFAULT_WARMUP,
                                       negative = none */
    int frames;                     /* timed frames; default 0 = BENCH_DEFAULT_FRAMES */
    int swell_tier;                 /* the ocean's (swell_ocean_stats): the baseline's shader
                                       labels */
    double scale;                   /* the render scale the frame uses; 0 = 1 */
    /* labels copied into the result */
    const char *scene, *quality, *geometry, *platform;
    const char *detile;             /* "on" | "off" (swell --detile); default "on" */
    const char *cpu_scope;          /* what frame does on the calling thread (static text) */
};

struct bench_result {
    char scene[64], tier[16], quality[16], geometry[16], path[16], platform[16], detile[8];
    char gl_renderer[128];
    int width, height, warmup, frames;
    double scale;                   /* render scale: 1, or the upscale's share of each side */
    double step_s;
    struct bench_stats frame;       /* the scene */
    struct bench_stats quad;        /* the baseline quad */
    double ratio;                   /* frame.median_ms / quad.median_ms */
    int cpu_valid;                  /* 0: cpu_instructions_per_frame is null (see notes) */
    double cpu_instructions_per_frame;
    const char *cpu_scope;          /* what the count covers (static text) */
    uint64_t bytes_gpu;             /* the ocean's GPU bytes (swell_ocean_stats gpu_bytes) */
    uint64_t budget_bytes;
    uint64_t bytes_streamed_per_frame;
    int vertices, triangles;
    char notes[512];
};

/* Warm-up, then frames timed scene/quad interleaved; fills out but for the ocean's sizes
 * (bytes_gpu, budget_bytes, bytes_streamed_per_frame, vertices, triangles: the caller's, from
 * swell_ocean_stats). The baseline's texture and buffer are the benchmark's own (not charged
 * to the ocean's budget) and freed before returning. */
int bench_run(const struct bench_desc *d, struct bench_result *out, struct swell_err *err);

/* The result as one JSON object (no trailing newline). Returns the length it needs (like
 * snprintf); the text is complete only when that is < cap. */
int bench_format_json(const struct bench_result *r, char *buf, size_t cap);
/* Written atomically (fs_write_atomic) with a trailing newline. */
int bench_write_json(const char *path, const struct bench_result *r, struct swell_err *err);
/* One line for people: scene, tier, quality, median/p95, baseline, ratio, CPU, GPU bytes. */
void bench_format_summary(const struct bench_result *r, char *buf, size_t cap);

#endif
