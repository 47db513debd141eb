/* upscale.h - render scale (swell --scale): the frame drawn into a smaller offscreen target,
 * then stretched over the output by one bilinear fetch a pixel.
 *
 * The trade of issue 15 item 4 for GPUs whose fragment rate cannot shade every output pixel
 * (Mali-400 MP2: low quality at 1920x1080 is ~8x short of 60 fps by docs/devices.md's cost
 * model): scale s shades s^2 of the pixels; the picture is the smaller frame, blurred by the
 * stretch. The renderer never knows: it draws a frame of the target's size as on any other.
 * The target is an RGBA8 texture of the scaled size (NPOT, no mips, clamped: GLES 2 core) with
 * a 16-bit depth buffer where the output has one (so the renderer draws as it would there).
 */
#ifndef SWELL_UPSCALE_H
#define SWELL_UPSCALE_H

#include "gl/gpu.h"
#include "gl/shader.h"

#define UPSCALE_MIN SWELL_UPSCALE_MIN    /* --scale range (swell.h) */
#define UPSCALE_MAX SWELL_UPSCALE_MAX

struct upscale {
    struct gpu *gpu;            /* accounting of the target */
    int w, h;                   /* the scaled frame, pixels */
    int out_w, out_h;           /* the output it is stretched over */
    GLuint fbo, tex, depth, vbo;
    struct shader_program prog;
    GLint u_frame;
    GLint target;               /* the output framebuffer bound when the frame began */
    int unit;                   /* the texture unit the stretch binds */
};

/* The scaled size of an output side: round(out x scale), at least 1. */
int upscale_side(int out, double scale);

/* Builds the target and the stretch for an output of out_w x out_h at scale (UPSCALE_MIN..1),
 * and draws the stretch once (a driver that refuses it is said so here, not at a frame: its
 * stderr is scanned as the renderer's probe does, and where draws execute the result is read
 * back). unit: the texture unit the stretch (and its probe) binds. depth_bits: the output's.
 * shader_dir NULL: found (core/datadir.h). */
int  upscale_create(struct upscale *u, struct gpu *g, int unit, int out_w, int out_h,
                    double scale, int depth_bits, const char *shader_dir, struct swell_err *err);
/* Before the frame is drawn: keeps the bound framebuffer as the output and binds the target. */
void upscale_begin(struct upscale *u);
/* After: the output bound again, the target stretched over all of it. */
int  upscale_end(struct upscale *u, struct swell_err *err);
void upscale_destroy(struct upscale *u);

#endif
