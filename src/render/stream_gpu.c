/* stream_gpu.c - the loop blend of the streamed slope and whitecap tables drawn on the GPU
 * (render/internal.h stream_gpu_*).
 *
 * Hu et al. 2006 loop the maps over F baked frames; each display frame shows the blend of the
 * two frames the phase lies between (tables/stream.h). Blended on the CPU, that was every
 * byte of every streamed chain each frame, then uploaded: at the surface in rough seas 722 KiB a
 * frame, 0.46 M instructions (low quality) and 0.90 M (high, whose whitecap tables stream too)
 * of the 2 M budget. Here each table keeps the two frames' chains as baked, as textures, and
 * a draw per mip level blends them into the texture the ocean reads (shaders_gles/
 * stream_blend.frag): a frame's chain is uploaded once when the phase reaches it (every
 * T_i / F seconds, T_i the pattern's period); the CPU blends and uploads only the levels under
 * GPU_BLEND_MIN texels, with the top texel whose moments the renderer's per-frame constants
 * need (textures.c slot_constants). What it costs the GPU: two nearest fetches and five
 * operations per texel of the levels it draws (87 040 texels a frame in low quality, 130 560
 * in high with the default budget's 128 x 128 tables: a seventh of a 1280x720 frame's pixels;
 * renderer_describe prints the count, tools/devices.py's cost model adds it), and the two
 * sources' memory per table.
 *
 * GLES 2 draws only into level 0 of a texture without OES_fbo_render_mipmap (GLES 3 and every
 * Mesa driver have it); where the renderer keeps one texture per level (run_lod) each level is
 * a level 0. Where neither, where the program is refused, the framebuffer is not complete or
 * the budget has no room for the sources, the CPU blends as before (gpu_blend_why says why).
 */
#include <stdlib.h>
#include <string.h>
#include "render/internal.h"

enum { BLEND_SLOPE, BLEND_WC };

/* Levels narrower and lower than this many texels are blended on the CPU and uploaded (a few
 * hundred bytes a table): a draw and a framebuffer change each cost a software rasteriser
 * more than their texels (llvmpipe, rough surface at 1280x720: every level drawn took the
 * frame 4-5 % longer than the CPU's blend) and a tiler a pass over its tile memory. */
#define GPU_BLEND_MIN 16

/* The first level of t the CPU blends (stream_blend_coarse): its levels from there up. */
static int first_cpu_level(const struct swell_table *t)
{
    int l = 0;
    while (l < t->levels - 1 && ((t->width >> l) >= GPU_BLEND_MIN || (t->height >> l) >= GPU_BLEND_MIN))
        l++;
    return l;
}

static const struct swell_table *blend_table(const struct fs_slot *sl, int k)
{
    return k == BLEND_SLOPE ? sl->slope : sl->wc;
}

static struct chain_tex *blend_dest(struct fs_slot *sl, int k)
{
    return k == BLEND_SLOPE ? &sl->slope_tex : &sl->wc_tex;
}

/* the tables a slot streams: its slopes, and its whitecaps where they have a texture */
static int blend_kinds(const struct fs_slot *sl)
{
    return sl->wc_tex.tex[0] ? 2 : 1;
}

void stream_gpu_destroy(struct renderer *r)
{
    for (int s = 0; s < r->nfs; s++)
        for (int k = 0; k < 2; k++)
            for (int i = 0; i < 2; i++) {
                gpu_texture_destroy(r->gpu, &r->slot[s].frame_tex[k][i]);
                r->slot[s].frame_of[k][i] = -1;
            }
    if (r->blend_fbo)
        glDeleteFramebuffers(1, &r->blend_fbo);
    r->blend_fbo = 0;
    shader_program_destroy(&r->blendp);
    r->gpu_blend = 0;
}

/* The CPU blends: why, the GPU's objects released, GL errors drained. */
static void use_cpu(struct renderer *r, const char *why)
{
    stream_gpu_destroy(r);
    gpu_check("renderer: loop blend on the GPU", NULL);
    r->gpu_blend_why = why;
}

/* level l of chain c as the framebuffer's colour: the chain's own level or level l's texture */
static void attach_level(const struct chain_tex *c, int l)
{
    glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, chain_at(c, l),
                           c->levels ? 0 : l);
}

/* the probe's draw: the blend over the first slot's sources (what they hold does not matter) */
static void probe_blend(void *ctx)
{
    struct renderer *r = ctx;
    int u0 = r->d.texture_unit_first;
    for (int i = 0; i < 2; i++) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)(u0 + i));
        glBindTexture(GL_TEXTURE_2D, r->slot[0].frame_tex[BLEND_SLOPE][i]);
    }
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    glUseProgram(r->blendp.program);
    glUniform1i(r->blend_u[0], u0);
    glUniform1i(r->blend_u[1], u0 + 1);
    glUniform3f(r->blend_u[2], 0.5f, 1.0f, 0.0f);
    glBindBuffer(GL_ARRAY_BUFFER, r->quad_vbo);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, (const void *)0);
    glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
    glDisableVertexAttribArray(0);
}

void stream_gpu_create(struct renderer *r)
{
    static const char *const names[3] = { "frame_a", "frame_b", "blend_w" };
    static const struct shader_attrib attribs[1] = { { "a_ndc", 0 } };
    const char *env = getenv("SWELL_LOOP_BLEND");
    r->gpu_blend = 0;
    for (int s = 0; s < r->nfs; s++)
        for (int k = 0; k < 2; k++)
            r->slot[s].frame_of[k][0] = r->slot[s].frame_of[k][1] = -1;
    if (r->d.cpu_loop_blend || (env && !strcmp(env, "cpu"))) {
        r->gpu_blend_why = "asked for: SWELL_LOOP_BLEND=cpu or the renderer's cpu_loop_blend";
        return;
    }
    if (r->nfs == 0) {
        r->gpu_blend_why = "no table is streamed";
        return;
    }
    if (!r->run_lod && !r->gpu->caps.fbo_render_mipmap) {
        r->gpu_blend_why = "the device draws into no mip level but the first "
                           "(no OES_fbo_render_mipmap)";
        return;
    }
    struct shader_desc sd = {
        .dir = r->d.shader_dir, .vs_file = "upscale.vert", .fs_file = "stream_blend.frag",
        .caps = &r->gpu->caps, .uniform_names = names, .uniform_count = 3,
        .uniform_locations = r->blend_u, .attribs = attribs, .attrib_count = 1,
    };
    /* the sources' room first: none made and released (the accounting's peak) where the
     * budget holds fewer */
    uint64_t need = 0;
    for (int s = 0; s < r->nfs; s++)
        for (int k = 0; k < blend_kinds(&r->slot[s]); k++)
            need += 2u * stream_blended_bytes(blend_table(&r->slot[s], k));
    if (r->gpu->budget_bytes && r->gpu->bytes + need > r->gpu->budget_bytes) {
        r->gpu_blend_why = "the GPU budget has no room for the loop frames' textures";
        return;
    }
    struct swell_err err;
    if (shader_program_build(&sd, &r->blendp, &err))
        return use_cpu(r, "the driver refused stream_blend.frag (its messages are above)");
    for (int s = 0; s < r->nfs; s++) {
        struct fs_slot *sl = &r->slot[s];
        for (int k = 0; k < blend_kinds(sl); k++) {
            const struct swell_table *t = blend_table(sl, k);
            for (int i = 0; i < 2; i++) {
                if (gpu_texture_create(r->gpu, t->width, t->height, t->levels, FORMAT_RGBA8, 0,
                                       "renderer: loop frame", &sl->frame_tex[k][i], &err))
                    return use_cpu(r, "the GPU budget has no room for the loop frames' "
                                      "textures");
                /* read at texel centres at the level the viewport's size gives: exact texels */
                glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
                glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST_MIPMAP_NEAREST);
            }
        }
    }
    GLint prev = 0;
    glGetIntegerv(GL_FRAMEBUFFER_BINDING, &prev);
    glGenFramebuffers(1, &r->blend_fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, r->blend_fbo);
    int complete = 1;
    const struct chain_tex *c = blend_dest(&r->slot[0], BLEND_SLOPE);
    for (int l = 0; l < 2 && l < r->slot[0].slope->levels; l++) {
        attach_level(c, l);
        complete &= glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)prev);
    if (!complete)
        return use_cpu(r, "a streamed table's level is not a complete framebuffer here");
    if (!gpu_probe_draw("loop blend", 16, probe_blend, NULL, r))
        return use_cpu(r, "the driver does not run stream_blend.frag (its messages are above)");
    if (gpu_check("renderer: loop blend on the GPU", NULL))
        return use_cpu(r, "a GL error setting the GPU's loop blend up");
    r->gpu_blend = 1;
    r->gpu_blend_why = NULL;
    r->blend_texels = 0;
    for (int s = 0; s < r->nfs; s++)
        for (int k = 0; k < blend_kinds(&r->slot[s]); k++) {
            const struct swell_table *t = blend_table(&r->slot[s], k);
            for (int l = 0; l < first_cpu_level(t); l++)
                r->blend_texels += (long)(t->width >> l > 0 ? t->width >> l : 1) *
                                   (t->height >> l > 0 ? t->height >> l : 1);
        }
}

/* Frame f of table t as baked into texture tex, every level (the table holds level-major
 * layers: each level of the frame is one contiguous image). */
static void upload_frame(GLuint tex, const struct swell_table *t, int f)
{
    glBindTexture(GL_TEXTURE_2D, tex);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (int l = 0; l < t->levels; l++) {
        int lw = t->width >> l > 0 ? t->width >> l : 1, lh = t->height >> l > 0 ? t->height >> l : 1;
        glTexSubImage2D(GL_TEXTURE_2D, l, 0, 0, lw, lh, GL_RGBA, GL_UNSIGNED_BYTE,
                        t->data + table_offset(t, l, f));
    }
}

/* Which of the pair holds frame f0 (a) and f1 (b), uploading what neither holds into the one
 * the other does not need. */
static void ensure_frames(struct fs_slot *sl, int k, int f0, int f1, int *a, int *b)
{
    const struct swell_table *t = blend_table(sl, k);
    int want[2] = { f0, f1 }, at[2];
    for (int j = 0; j < 2; j++)
        at[j] = sl->frame_of[k][0] == want[j] ? 0 : sl->frame_of[k][1] == want[j] ? 1 : -1;
    for (int j = 0; j < 2; j++) {
        if (at[j] >= 0)
            continue;
        int i = at[1 - j] == 0 ? 1 : 0;   /* the one the other frame is not in */
        upload_frame(sl->frame_tex[k][i], t, want[j]);
        sl->frame_of[k][i] = want[j];
        at[j] = i;
    }
    *a = at[0];
    *b = at[1];
}

void stream_gpu_slot(struct renderer *r, struct fs_slot *sl, const struct stream_phase *ph)
{
    struct pass_saved saved;
    int u0 = r->d.texture_unit_first;
    float w = (float)ph->w / (float)STREAM_W_ONE;
    pass_save(&saved);
    pass_quad_begin(r, r->blend_fbo, r->blendp.program);
    glUniform1i(r->blend_u[0], u0);
    glUniform1i(r->blend_u[1], u0 + 1);
    for (int k = 0; k < blend_kinds(sl); k++) {
        const struct swell_table *t = blend_table(sl, k);
        int f0 = ph->f0 < t->layers ? ph->f0 : 0, f1 = ph->f1 < t->layers ? ph->f1 : 0, a, b;
        ensure_frames(sl, k, f0, f1, &a, &b);
        glActiveTexture(GL_TEXTURE0 + (GLenum)u0);
        glBindTexture(GL_TEXTURE_2D, sl->frame_tex[k][a]);
        glActiveTexture(GL_TEXTURE0 + (GLenum)(u0 + 1));
        glBindTexture(GL_TEXTURE_2D, sl->frame_tex[k][b]);
        int coarse = first_cpu_level(t);
        for (int l = 0; l < coarse; l++) {
            int lw = t->width >> l > 0 ? t->width >> l : 1;
            int lh = t->height >> l > 0 ? t->height >> l : 1;
            attach_level(blend_dest(sl, k), l);
            glViewport(0, 0, lw, lh);
            /* the whitecap blend's own variance in channel 2 of levels 0 and 1 (stream.h) */
            int mix = k == BLEND_WC && l < 2;
            glUniform3f(r->blend_u[2], w, mix ? 4.0f * w * (1.0f - w) : 0.0f, mix ? 0.0f : 1.0f);
            glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
        }
    }
    glDisableVertexAttribArray(0);
    pass_restore(&saved);
    /* the coarse levels on the CPU, uploaded (the top texel's moments stay in the buffer) */
    glActiveTexture(GL_TEXTURE0 + (GLenum)u0);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (int k = 0; k < blend_kinds(sl); k++) {
        const struct swell_table *t = blend_table(sl, k);
        const struct chain_tex *c = blend_dest(sl, k);
        uint8_t *buf = k == BLEND_SLOPE ? sl->slope_b : sl->wc_b;
        int from = first_cpu_level(t);
        if (k == BLEND_WC)
            stream_blend_whitecap_coarse(t, ph, from, buf);
        else
            stream_blend_coarse(t, ph, from, buf);
        for (int l = from; l < t->levels; l++) {
            int lw = t->width >> l > 0 ? t->width >> l : 1;
            int lh = t->height >> l > 0 ? t->height >> l : 1;
            glBindTexture(GL_TEXTURE_2D, chain_at(c, l));
            glTexSubImage2D(GL_TEXTURE_2D, c->levels ? 0 : l, 0, 0, lw, lh, GL_RGBA,
                            GL_UNSIGNED_BYTE, buf + stream_level_offset(t, l));
        }
    }
}
