/* textures.c - the renderer's textures (render/internal.h): the tables' mip chains (one
 * texture per level for one LOD per run), the Fresnel atlas of the effective-Fresnel tables
 * (Bruneton eq. 26 as baked), the displacement textures of the vertex-texture-fetch tiers, and
 * the per-frame streaming of loop-blended tables (tables/stream.h); every object accounted
 * through gl/gpu.h.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "render/internal.h"

/* A table of levels mips (levels 1: none) as one texture, or with run_lod one per level. */
static int chain_create(struct renderer *r, int w, int h, int levels, int format, int repeat,
                        const char *what, struct chain_tex *c, struct swell_err *err)
{
    int rc;
    memset(c, 0, sizeof(*c));
    if (!r->run_lod || levels <= 1)
        return gpu_texture_create(r->gpu, w, h, levels, format, repeat, what, &c->tex[0], err);
    if (levels > SLOT_LEVELS)
        return swell_fail(err, SWELL_E_ARG, "%s: %d mip levels, at most %d", what, levels,
                          SLOT_LEVELS);
    for (int l = 0; l < levels; l++) {
        int lw = w >> l > 0 ? w >> l : 1, lh = h >> l > 0 ? h >> l : 1;
        if ((rc = gpu_texture_create(r->gpu, lw, lh, 1, format, repeat, what, &c->tex[l], err)))
            return rc;
        c->levels = l + 1;
    }
    return 0;
}

void chain_destroy(struct renderer *r, struct chain_tex *c)
{
    for (int l = SLOT_LEVELS - 1; l >= 0; l--)
        gpu_texture_destroy(r->gpu, &c->tex[l]);
    c->levels = 0;
}

/* The texture to bind for fetches at level l (the chain itself, which the shader or the
 * hardware takes its level from, or level l's own). */
GLuint chain_at(const struct chain_tex *c, int l)
{
    if (c->levels == 0)
        return c->tex[0];
    return c->tex[l < 0 ? 0 : l < c->levels ? l : c->levels - 1];
}

void bind_tex(const struct renderer *r, int unit, GLuint tex, GLint loc)
{
    unit += r->d.texture_unit_first;      /* the application's choice (renderer_desc) */
    glActiveTexture(GL_TEXTURE0 + (GLenum)unit);
    glBindTexture(GL_TEXTURE_2D, tex);
    if (loc >= 0)
        glUniform1i(loc, unit);
}

/* A texture's mip chain, level-major and tightly packed: RGBA8, or with type the GL half-float
 * type, RGBA16F (upload_chain_typed); into the chain's texture, or each level's own. */
int upload_chain_typed(const struct chain_tex *c, int w, int h, int levels,
                       const void *data, GLenum type, const char *what,
                       struct swell_err *err)
{
    size_t off = 0, texel = type == GL_UNSIGNED_BYTE ? 4 : 8;
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (int l = 0; l < levels; l++) {
        int lw = w >> l > 0 ? w >> l : 1, lh = h >> l > 0 ? h >> l : 1;
        if (l == 0 || c->levels)
            glBindTexture(GL_TEXTURE_2D, chain_at(c, l));
        glTexSubImage2D(GL_TEXTURE_2D, c->levels ? 0 : l, 0, 0, lw, lh, GL_RGBA, type,
                        (const uint8_t *)data + off);
        off += texel * (size_t)lw * lh;
    }
    return gpu_check(what, err);
}

int upload_chain(const struct chain_tex *c, int w, int h, int levels,
                 const uint8_t *data, const char *what, struct swell_err *err)
{
    return upload_chain_typed(c, w, h, levels, data, GL_UNSIGNED_BYTE, what, err);
}

/* A texture without mips (levels 1 of upload_chain). */
int upload_single(GLuint tex, int w, int h, const uint8_t *data, const char *what,
                  struct swell_err *err)
{
    struct chain_tex c = { { tex }, 0 };
    return upload_chain(&c, w, h, 1, data, what, err);
}

/* The Fresnel textures are an atlas (detile.h): the F x F Fresnel texels in rows [0, F), row F a
 * copy of row F - 1 (a bilinear lookup at the disc's edge, fresnel_uv_scale, reads no hash), the
 * lattice hash's cells (detile_cell_table) in rows [F + 1, F + 1 + DETILE_N), columns
 * [0, DETILE_N); with a wave mask (mask.c) its MASK_TEX-square block from column mask_x, rows
 * [0, MASK_TEX); POT. ocean.frag reads all of them through one unit: gles2-min's 8 are all in
 * use, and a unit of the mask's own moved a wave pattern to the CPU there (+3.3 M instructions
 * a frame in high quality, callgrind: the mask's view of README.md). */
static void atlas_size(const struct swell_table *fr, int mask, int *w, int *h, int *mask_x)
{
    int need = fr->height + 1 + DETILE_N;
    *w = fr->width > DETILE_N ? fr->width : DETILE_N;
    *mask_x = 0;
    if (mask) {
        *mask_x = *w > fr->width ? *w : fr->width + 1;   /* after the guard column */
        int wide = *mask_x + MASK_TEX;
        for (*w = 1; *w < wide; *w *= 2)
            ;
        need = need > MASK_TEX ? need : MASK_TEX;
    }
    for (*h = 1; *h < need; *h *= 2)
        ;
}

/* out (atlas_w x atlas_h RGBA8) holds the Fresnel rows; add the guard row and the hash. */
static void atlas_finish(const struct renderer *r, uint8_t *out)
{
    const struct swell_table *fr = r->fresnel;
    size_t row = 4 * (size_t)r->atlas_w;
    memset(out + row * (size_t)fr->height, 0, row * (size_t)(r->atlas_h - fr->height));
    for (int y = 0; r->atlas_w > fr->width && y < fr->height; y++)   /* a guard column too */
        memcpy(out + row * (size_t)y + 4 * (size_t)fr->width,
               out + row * (size_t)y + 4 * (size_t)(fr->width - 1), 4);
    memcpy(out + row * (size_t)fr->height, out + row * (size_t)(fr->height - 1), row);
    detile_cell_table(out + row * (size_t)(fr->height + 1), row);
    if (r->d.wave_mask)
        mask_block(&r->mask, out + 4 * (size_t)r->mask_x, row);
}

/* Where the atlas's hash is, for ocean.frag's detile_atlas and ocean.vert's detile_atlas_v:
 * 1 / its size and the hash rows' origin v. */
void atlas_hash_frame(const struct renderer *r, float out[4])
{
    out[0] = 1.0f / (float)r->atlas_w;
    out[1] = 1.0f / (float)r->atlas_h;
    out[2] = (float)(r->fresnel->height + 1) / (float)r->atlas_h;
    out[3] = 0.0f;
}

static int upload_atlas(const struct renderer *r, GLuint tex, uint8_t *atlas,
                        struct swell_err *err)
{
    atlas_finish(r, atlas);
    return upload_single(tex, r->atlas_w, r->atlas_h, atlas, "renderer: Fresnel upload", err);
}

static int create_disp_textures(struct renderer *r, struct swell_err *err)
{
    for (int i = 0; i < r->t->patterns; i++) {
        const struct swell_table *d = tables_find(r->t, TABLE_DISP, i);
        for (int k = 0; k < 2; k++) {
            int rc = gpu_texture_create(r->gpu, d->width, d->height, 1, FORMAT_RGBA8, 1,
                                        "renderer: displacement (vertex shader)",
                                        &r->disp_tex[i][k], err);
            if (rc)
                return rc;
            r->disp_frame[i][k] = -1;
        }
    }
    return 0;
}

/* Make the pair of pattern i hold loop frames f0 and f1, uploading only a frame it lacks. */
void stream_disp(struct renderer *r, double t_s)
{
    for (int i = 0; i < r->t->patterns; i++) {
        const struct swell_table *d = tables_find(r->t, TABLE_DISP, i);
        struct stream_phase ph;
        int want[2], *have = r->disp_frame[i];
        stream_pattern_phase(r->t, i, t_s, r->t->frames, &ph);
        want[0] = ph.f0 < d->layers ? ph.f0 : 0;
        want[1] = ph.f1 < d->layers ? ph.f1 : 0;
        for (int k = 0; k < 2; k++) {
            int slot = have[0] == want[k] ? 0 : have[1] == want[k] ? 1 : -1;
            if (slot < 0) {
                /* replace the one the other wanted frame is not in */
                slot = (have[0] == want[1 - k]) ? 1 : 0;
                have[slot] = want[k];
                upload_single(r->disp_tex[i][slot], d->width, d->height,
                       d->data + table_offset(d, 0, want[k]), "renderer: displacement",
                              NULL);
            }
            r->disp_ab[i][k] = slot;
        }
        r->disp_w[i] = (float)ph.w / STREAM_W_ONE;
    }
}

int create_textures(struct renderer *r, struct swell_err *err)
{
    const struct swell_table *fr = tables_find(r->t, TABLE_FRESNEL, -1);
    int rc;
    if (!fr) {
        if ((rc = fresnel_hu_table(FRESNEL_FALLBACK, &r->fresnel_own, err)))
            return rc;
        fr = &r->fresnel_own;
    }
    r->fresnel = fr;
    atlas_size(fr, r->d.wave_mask, &r->atlas_w, &r->atlas_h, &r->mask_x);
    if ((rc = sky_bake(r->d.sun_elev_deg, r->d.sun_azim_deg, SKY_MAP_SIZE, &r->sky, err)))
        return rc;
    size_t scratch = sky_level_offset(&r->sky, r->sky.levels);
    if (scratch < 4 * (size_t)r->atlas_w * r->atlas_h)
        scratch = 4 * (size_t)r->atlas_w * r->atlas_h;
    if (!(r->scratch = malloc(scratch)))
        return swell_fail(err, SWELL_E_NOMEM, "renderer: no memory for derived textures");
    for (int y = 0; y < fr->height; y++)
        memcpy(r->scratch + 4 * (size_t)r->atlas_w * y, fr->data + 4 * (size_t)fr->width * y,
               4 * (size_t)fr->width);
    if ((rc = gpu_texture_create(r->gpu, r->atlas_w, r->atlas_h, 1, FORMAT_RGBA8, 0,
                                 "renderer: Fresnel texture", &r->fresnel_tex, err)) ||
        (rc = upload_atlas(r, r->fresnel_tex, r->scratch, err)))
        return rc;
    update_sky_constants(r);
    if ((rc = gpu_texture_create(r->gpu, SKY_VIEW_N, 2, 1, FORMAT_RGBA8, 0,
                                 "renderer: background sky table", &r->sky_view_tex, err)))
        return rc;
    r->sky_half = r->gpu->caps.half_float;
    int sky_format = r->sky_half ? FORMAT_RGBA16F : FORMAT_RGBA8;
    if ((rc = r->run_lod ? gpu_texture_create(r->gpu, 2 * SKY_MAP_SIZE, SKY_MAP_SIZE, 1,
                                              sky_format, 0, "renderer: sky map atlas",
                                              &r->sky_tex.tex[0], err)
                         : chain_create(r, SKY_MAP_SIZE, SKY_MAP_SIZE, r->sky.levels, sky_format,
                                        0, "renderer: sky map", &r->sky_tex, err)) ||
        (rc = upload_sky(r, &r->sky, err)))
        return rc;
    if (r->vtf && (rc = create_disp_textures(r, err)))
        return rc;
    for (int s = 0; s < r->nfs; s++) {
        struct fs_slot *sl = &r->slot[s];
        if (!sl->slope || !sl->wc || sl->slope->format != FORMAT_RGBA8 ||
            sl->wc->format != FORMAT_RGBA8)
            return swell_fail(err, SWELL_E_FORMAT, "renderer: pattern %d lacks rgba8 slope or "
                              "whitecap tables; re-bake for the gles2-min format", sl->pattern);
        if ((rc = chain_create(r, sl->slope->width, sl->slope->height, sl->slope->levels,
                               FORMAT_RGBA8, 1, "renderer: slope", &sl->slope_tex, err)))
            return rc;
        if (!(sl->slope_b = malloc(stream_blended_bytes(sl->slope))))
            return swell_fail(err, SWELL_E_NOMEM, "renderer: no memory to blend slopes");
        r->stream_bytes += stream_blended_bytes(sl->slope);
        if (s >= r->nwc)
            continue;
        if ((rc = chain_create(r, sl->wc->width, sl->wc->height, sl->wc->levels, FORMAT_RGBA8,
                               1, "renderer: whitecap", &sl->wc_tex, err)))
            return rc;
        if (!(sl->wc_b = malloc(stream_blended_bytes(sl->wc))))
            return swell_fail(err, SWELL_E_NOMEM, "renderer: no memory to blend whitecaps");
        r->stream_bytes += stream_blended_bytes(sl->wc);
    }
    return 0;
}

/* Dequantised first texel of the top (1x1) level of a blended chain or, for a table that is
 * not streamed, of the table itself (constant tables only reach here unstreamed). */
static void top_texel(const struct swell_table *t, const uint8_t *chain, float out[4])
{
    const uint8_t *px = chain ? chain + stream_level_offset(t, t->levels - 1)
                              : t->data + table_offset(t, t->levels - 1, 0);
    for (int c = 0; c < 4; c++)
        out[c] = t->bias[c] + t->scale[c] * (float)px[c] * (1.0f / 255.0f);
}

/* A slot's moments where its pattern is not fetched: mean and variance over the whole patch. */
static void slot_constants(struct fs_slot *sl)
{
    float m[4];
    top_texel(sl->slope, sl->slope_b, m);
    sl->top_slope[0] = m[0];
    sl->top_slope[1] = m[1];
    sl->top_slope[2] = fmaxf(m[2] - m[0] * m[0], 0.0f);
    sl->top_slope[3] = fmaxf(m[3] - m[1] * m[1], 0.0f);
    top_texel(sl->wc, sl->wc_tex.tex[0] ? sl->wc_b : NULL, m);
    sl->top_k[0] = m[0];
    sl->top_k[1] = fmaxf(m[1] - m[0] * m[0], 0.0f);
}

void stream_textures(struct renderer *r, double t_s)
{
    for (int s = 0; s < r->nfs; s++) {
        struct fs_slot *sl = &r->slot[s];
        struct stream_phase ph;
        stream_pattern_phase(r->t, sl->pattern, t_s, r->t->frames, &ph);
        if (sl->phase_valid && ph.f0 == sl->phase.f0 && ph.w == sl->phase.w)
            continue;
        sl->phase = ph;
        sl->phase_valid = 1;
        if (r->gpu_blend) {
            /* the GPU blends the chains' fine levels, the CPU the coarse ones (stream_gpu.c),
             * with the top texel whose moments slot_constants takes */
            stream_gpu_slot(r, sl, &ph);
            slot_constants(sl);
            continue;
        }
        stream_blend(sl->slope, &ph, sl->slope_b);
        upload_chain(&sl->slope_tex, sl->slope->width, sl->slope->height, sl->slope->levels,
              sl->slope_b, "renderer: slope stream", NULL);
        if (sl->wc_tex.tex[0]) {
            stream_blend_whitecap(sl->wc, &ph, sl->wc_b);
            upload_chain(&sl->wc_tex, sl->wc->width, sl->wc->height, sl->wc->levels, sl->wc_b,
                  "renderer: whitecap stream", NULL);
        }
        slot_constants(sl);
    }
}
