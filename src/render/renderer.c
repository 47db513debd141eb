/* renderer.c - the renderer's life: creation (paths chosen from the device's tier and the
 * start-up probe), the sun, statistics and description, destruction (renderer.h).
 *
 * gles2-min path (DESIGN.md): the CPU builds the geometry (geometry/grid.c: projected grid or
 * near/far patches, displaced by the looping tables with Bruneton eq. 2 weights) and streams it
 * into one VBO per frame; loop frames of the slope and whitecap tables are blended on the CPU
 * (tables/stream.c) into one texture per pattern and kind; patterns without a free texture unit
 * are resolved per vertex. Sky: analytic, baked once into a stereographic map (optics/sky.c).
 * Shading: ocean.frag. The renderer is one struct (render/internal.h) worked on by:
 *   renderer.c  create, destroy, set_sun, stats, describe
 *   programs.c  the ocean, sky and sun programs, their variants and the start-up probe
 *   slots.c     patterns to fragment slots, their tables' per-level statistics
 *   textures.c  GL textures of the tables: upload, the Fresnel atlas, streaming each frame
 *   sky_draw.c  the sky map and background sky: upload, exposure constants, draw
 *   lod.c       levels per run of rows: which patterns a run fetches, and at what level
 *   frame.c     one frame: the vertex terms, the ocean uniforms, the runs of rows
 *
 * Fetches are the cost on fill-rate-bound GPUs (and llvmpipe): the sea is drawn as runs of grid
 * rows, far to near, each with the ocean.frag variant that fetches only the patterns not yet
 * fully filtered there. Where a pixel covers a whole patch of pattern i (footprint >= L_i) its
 * mip chain is at the top level, the patch's mean slope and slope variance (Bruneton §4.1; the
 * same for Dupuy's k moments), so the variant takes those as constants. Whitecap tables are
 * fetched only for patterns that carry whitecaps (the others' tables are constant).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "core/parse.h"
#include "render/internal.h"

static const char *const quality_names[QUALITY_COUNT] = { "high", "low" };

const char *render_quality_name(int q) { return name_of(quality_names, QUALITY_COUNT, q); }
int render_quality_from_name(const char *name)
{
    return parse_name(quality_names, 0, QUALITY_COUNT, name);
}
int renderer_detile(const struct renderer *r)
{
    return r->d.detile == DETILE_MODE_ON;
}

static void resolve(struct renderer_desc *d)
{
    if (d->grid_w <= 0)
        d->grid_w = 80;
    if (d->grid_h <= 0)
        d->grid_h = 56;
    if (d->sun_elev_deg == 0.0f)
        d->sun_elev_deg = 30.0f;
    if (d->detile == DETILE_MODE_AUTO)
        d->detile = d->quality == QUALITY_HIGH ? DETILE_MODE_ON : DETILE_MODE_OFF;
}

void renderer_destroy(struct renderer *r)
{
    if (!r)
        return;
    stream_gpu_destroy(r);
    for (int s = SWELL_MAX_PATTERNS - 1; s >= 0; s--) {
        gpu_texture_destroy(r->gpu, &r->disp_tex[s][1]);
        gpu_texture_destroy(r->gpu, &r->disp_tex[s][0]);
        chain_destroy(r, &r->slot[s].wc_tex);
        chain_destroy(r, &r->slot[s].slope_tex);
        free(r->slot[s].wc_b);
        free(r->slot[s].slope_b);
    }
    gpu_buffer_destroy(r->gpu, &r->sky_ibo);
    gpu_buffer_destroy(r->gpu, &r->sky_vbo);
    gpu_buffer_destroy(r->gpu, &r->quad_vbo);
    gpu_buffer_destroy(r->gpu, &r->ibo);
    gpu_buffer_destroy(r->gpu, &r->vbo);
    gpu_texture_destroy(r->gpu, &r->sky_view_tex);
    chain_destroy(r, &r->sky_tex);
    gpu_texture_destroy(r->gpu, &r->fresnel_tex);
    reflect_destroy(r);
    wake_destroy(r);
    free(r->mask_bytes);
    shadow_destroy(r);
    refract_destroy(r);
    free(r->scratch);
    shader_program_destroy(&r->sunp);
    shader_program_destroy(&r->skyp);
    for (int v = OCEAN_VARIANTS - 1; v >= 0; v--)
        shader_program_destroy(&r->ocean[v]);
    free(r->fresnel_own.data);
    free(r->verts);
    free(r->shaded);
    sky_destroy(&r->sky);
    grid_destroy(r->grid);
    free(r);
}

static int create_buffers(struct renderer *r, struct swell_err *err)
{
    static const float quad[8] = { -1.0f, -1.0f, 1.0f, -1.0f, -1.0f, 1.0f, 1.0f, 1.0f };
    /* VTF: a static (i, j) / (w - 1, h - 1) per vertex; else the streamed CPU vertices, grid.c's
     * and vshade.c's from them */
    size_t nv = (size_t)grid_vertex_count(r->grid);
    size_t vbytes = sizeof(float) * (r->vtf ? 2 : r->cpu_vterms ? VSHADE_FLOATS : GRID_FLOATS) * nv;
    size_t gbytes = sizeof(float) * (r->vtf ? 2 : GRID_FLOATS) * nv;
    size_t ibytes = sizeof(uint16_t) * (size_t)grid_index_count(r->grid);
    int rc;
    if (!(r->verts = calloc(1, gbytes)) || (r->cpu_vterms && !(r->shaded = calloc(1, vbytes))))
        return swell_fail(err, SWELL_E_NOMEM, "renderer: no memory for %zu vertex bytes",
                          vbytes + gbytes);
    if ((rc = gpu_buffer_create(r->gpu, GL_ARRAY_BUFFER, vbytes,
                                r->vtf ? GL_STATIC_DRAW : GL_STREAM_DRAW,
                                r->vtf ? "renderer: sea grid parameters" : "renderer: sea vertices",
                                &r->vbo, err)) ||
        (rc = gpu_buffer_create(r->gpu, GL_ELEMENT_ARRAY_BUFFER, ibytes, GL_STATIC_DRAW,
                                "renderer: sea indices", &r->ibo, err)) ||
        (rc = gpu_buffer_create(r->gpu, GL_ARRAY_BUFFER, sizeof(quad), GL_STATIC_DRAW,
                                "renderer: sun quad", &r->quad_vbo, err)) ||
        (rc = create_sky_mesh(r, err)))
        return rc;
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, r->ibo);
    glBufferSubData(GL_ELEMENT_ARRAY_BUFFER, 0, (GLsizeiptr)ibytes, grid_indices(r->grid));
    glBindBuffer(GL_ARRAY_BUFFER, r->quad_vbo);
    glBufferSubData(GL_ARRAY_BUFFER, 0, sizeof(quad), quad);
    if (r->vtf) {
        int w = r->d.grid_w, h = r->d.grid_h;
        for (int j = 0; j < h; j++)
            for (int i = 0; i < w; i++) {
                r->verts[2 * (j * w + i)] = (float)i / (float)(w - 1);
                r->verts[2 * (j * w + i) + 1] = (float)j / (float)(h - 1);
            }
        glBindBuffer(GL_ARRAY_BUFFER, r->vbo);
        glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)vbytes, r->verts);
    }
    return gpu_check("renderer: buffer upload", err);
}

static int create_once(const struct renderer_desc *desc, struct renderer **out,
                       struct swell_err *err)
{
    struct renderer *r;
    struct grid_desc gd = { 0 };
    int rc;
    *out = NULL;
    if (!desc || !desc->tables || !desc->gpu)
        return swell_fail(err, SWELL_E_ARG, "renderer: descriptor needs tables and a gpu");
    if (desc->quality < 0 || desc->quality >= QUALITY_COUNT || desc->geometry < 0 ||
        desc->geometry >= GEOMETRY_COUNT || desc->detile < 0 || desc->detile >= DETILE_MODE_COUNT)
        return swell_fail(err, SWELL_E_ARG, "renderer: quality %d / geometry %d / detile %d out "
                          "of range", desc->quality, desc->geometry, desc->detile);
    GLint combined = 0;
    glGetIntegerv(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, &combined);
    int first = desc->texture_unit_first, count = desc->texture_unit_count;
    int least = UNIT_PATTERNS_OF(desc->reflections, desc->wakes, desc->shadows,
                                 desc->refractions) + 1;
    if (first < 0 || count < 0 || (count > 0 && count < least) ||
        first + (count > 0 ? count : least) > combined)
        return swell_fail(err, SWELL_E_ARG, "renderer: texture units %d..%d: the device has "
                          "%d (0..%d), and the sea needs %d at least", first,
                          first + (count > 0 ? count : least) - 1, (int)combined,
                          (int)combined - 1, least);
    glActiveTexture(GL_TEXTURE0 + (GLenum)first);   /* uploads: on the renderer's units */
    if (!(r = calloc(1, sizeof(*r))))
        return swell_fail(err, SWELL_E_NOMEM, "renderer: no memory");
    r->d = *desc;
    water_albedo(WATER_CHLOROPHYLL_OPEN, r->water_albedo);
    resolve(&r->d);
    uint64_t before = desc->gpu->bytes;
    r->gpu = desc->gpu;
    r->t = desc->tables;
    assign_patterns(r);
    if (r->t->has_foam_bias)
        r->foam_bias = r->t->foam_bias;
    else
        foam_bias_compute(r->t, &r->foam_bias);
    r->vtf = choose_vtf(r);
    r->cpu_vterms = !r->vtf && r->d.cpu_vertex_terms;
    r->run_lod = r->gpu->caps.prefer_run_lod && !r->d.pixel_lod;
    gd.tables = r->t;
    gd.kind = r->d.geometry;
    gd.w = r->d.grid_w;
    gd.h = r->d.grid_h;
    gd.cpu_patterns = r->cpu_mask;
    r->k_mask = low_foam_mask(r);   /* never with vtf (choose_vtf) */
    gd.k_patterns = r->k_mask;
    gd.no_detile = !renderer_detile(r);
    if ((rc = grid_create(&gd, &r->grid, err)) || (rc = create_textures(r, err)) ||
        (rc = reflect_create(r, err)) || (rc = wake_create(r, err)) ||
        (rc = shadow_create(r, err)) || (rc = refract_create(r, err)) ||
        (rc = build_programs(r, err)) || (rc = create_buffers(r, err)) ||
        (rc = probe_programs(r, err)))
        goto fail;
    stream_gpu_create(r);   /* after the probes, which blend on the CPU */
    r->gpu_bytes = r->gpu->bytes - before;
    *out = r;
    return 0;
fail:
    swell_err_context(err, "renderer_create");
    renderer_destroy(r);
    return rc;
}

/* One build for renderer_create: 0 and the number of programs refused in *refused, or its
 * error; a driver that runs none of them (SWELL_E_SHADER) counts as refusing all, with no
 * renderer. */
static int create_try(const struct renderer_desc *d, struct renderer **out, int *refused,
                      struct swell_err *err)
{
    int rc = create_once(d, out, err);
    *refused = rc == 0 ? (*out)->refused : OCEAN_VARIANTS + 1;
    return rc == SWELL_E_SHADER ? 0 : rc;
}

/* Where the driver refuses ocean programs (issue 15), built again in the ways that may fit,
 * in order: on gles2-min the terms of each vertex on the CPU (vshade.h: Vivante GC2000 refuses
 * ocean.vert's past its 256 instructions; costs CPU time, not the picture); with --detile auto,
 * without the lattice of random offsets (VideoCore IV runs 7 of high quality's 12 programs
 * with it, 12 without: each pattern then repeats on its tile, the lesser loss than the
 * patterns a refused program's rows go without); both (GC2000: 1, 3 with the CPU's terms, 12
 * with both). The first build the driver refuses nothing of is kept, else the one it refuses
 * least of (the earliest of those): one renderer at a time, so the GPU budget holds. */
int renderer_create(const struct renderer_desc *desc, struct renderer **out, struct swell_err *err)
{
    struct swell_err first_err = { 0 };
    int first, rc = create_try(desc, out, &first, &first_err);
    if (rc || first == 0) {
        if (err)
            *err = first_err;
        return rc;
    }
    /* what the first build resolved (create_once): vertex texture fetch leaves no vertex
     * terms to move; auto's lattice is on in high quality */
    struct renderer_desc probe_d = *desc;
    resolve(&probe_d);
    int vtf = *out ? (*out)->vtf : 0, cpu = *out ? (*out)->cpu_vterms : desc->cpu_vertex_terms;
    struct renderer_desc tries[3];
    int n = 0, can_cpu = !vtf && !cpu;
    int can_off = desc->detile == DETILE_MODE_AUTO && probe_d.detile == DETILE_MODE_ON;
    if (can_cpu) {
        tries[n] = *desc;
        tries[n++].cpu_vertex_terms = 1;
    }
    if (can_off) {
        tries[n] = *desc;
        tries[n++].detile = DETILE_MODE_OFF;
    }
    if (can_cpu && can_off) {
        tries[n] = tries[n - 1];
        tries[n++].cpu_vertex_terms = 1;
    }
    int best = -1, best_refused = first, cur = -1;   /* -1: desc itself */
    for (int i = 0; i < n && best_refused > 0; i++) {
        int refused;
        if (*out)
            renderer_destroy(*out);
        *out = NULL;
        cur = i;
        if ((rc = create_try(&tries[i], out, &refused, err)))
            return rc;
        if (refused < best_refused) {
            best = i;
            best_refused = refused;
        }
    }
    if (best_refused > OCEAN_VARIANTS) {   /* none runs any: the first build's message */
        if (*out)
            renderer_destroy(*out);
        *out = NULL;
        if (err)
            *err = first_err;
        return SWELL_E_SHADER;
    }
    if (cur != best || !*out) {
        if (*out)
            renderer_destroy(*out);
        *out = NULL;
        if ((rc = create_once(best < 0 ? desc : &tries[best], out, err)))
            return rc;
    }
    if (best >= 0) {
        (*out)->detile_refused = renderer_detile(*out) ? 0 : first;
        if (first > OCEAN_VARIANTS)
            fprintf(stderr, "swell: built again as%s: the driver refuses %d ocean program(s), "
                    "not all\n", program_tags(*out), (*out)->refused);
        else
            fprintf(stderr, "swell: built again as%s: the driver refuses %d ocean program(s), "
                    "not %d\n", program_tags(*out), (*out)->refused, first);
    }
    if (err)
        memset(err, 0, sizeof(*err));   /* a try that failed on the way is no error */
    return 0;
}

int renderer_set_sun(struct renderer *r, float elev_deg, float azim_deg, struct swell_err *err)
{
    struct sky fresh;
    if (!(elev_deg > 0.0f && elev_deg <= 90.0f) || !isfinite(azim_deg))
        return swell_fail(err, SWELL_E_ARG, "renderer_set_sun: elevation %g deg must be in (0, "
                          "90] and azimuth %g deg finite", (double)elev_deg, (double)azim_deg);
    /* bake first: a failure leaves the current sky in place */
    int rc = sky_bake(elev_deg, azim_deg, SKY_MAP_SIZE, &fresh, err);
    if (rc)
        return rc;
    glActiveTexture(GL_TEXTURE0 + (GLenum)r->d.texture_unit_first);   /* the upload's unit */
    if (r->sky_tex.tex[0] && (rc = upload_sky(r, &fresh, err))) {
        sky_destroy(&fresh);
        return rc;
    }
    sky_destroy(&r->sky);
    r->sky = fresh;
    r->d.sun_elev_deg = elev_deg;
    r->d.sun_azim_deg = azim_deg;
    update_sky_constants(r);
    return 0;
}

void renderer_get_stats(const struct renderer *r, struct renderer_stats *out)
{
    memset(out, 0, sizeof(*out));
    out->gpu_bytes = r->gpu_bytes;
    out->cpu_bytes_per_frame = (r->gpu_blend ? 0 : r->stream_bytes) + (r->vtf ? 0 :
        sizeof(float) * (r->cpu_vterms ? VSHADE_FLOATS : GRID_FLOATS) *
        (uint64_t)grid_vertex_count(r->grid));
    out->cpu_vertex_terms = r->cpu_vterms;
    out->vertices = grid_vertex_count(r->grid);
    out->triangles = grid_index_count(r->grid) / 3;
    out->sea_draws = r->draws;
    out->sea_draws_wc_const = r->draws_wc_const;
    out->sea_draws_resolved_drop = r->draws_resolved_drop;
    out->run_lod = r->run_lod;
    out->vtf = r->vtf;
    out->detile = renderer_detile(r);
    out->camera_raise_m = r->camera_raise_m;
    out->refused = r->refused;
}

void renderer_describe(const struct renderer *r, char *buf, size_t size)
{
    char blend_note[64] = "";
    if (r->gpu_blend)
        snprintf(blend_note, sizeof blend_note, ", %ld texels drawn a frame", r->blend_texels);
    int n = snprintf(buf, size,
        "tier: %s (%d texture units)\n"
        "geometry: %s, %s, %d vertices\n"
        "patterns: %d in the fragment shader, %d resolved per vertex (mask 0x%x), whitecaps "
        "per vertex of mask 0x%x\n"
        "loop frames: %s%s%s%s%s, %llu bytes of textures in a step's blend\n"
        "fetches: per run of rows only the patterns whose mip means still vary there; "
        "whitecaps of %d pattern(s); %s\n"
        "tiles: %s\n"
        "fragment precision: %s\n"
        "sky map: %s\n"
        "shading: %s\n",
        gpu_tier_name(r->gpu->caps.tier), r->gpu->caps.texture_units,
        geometry_kind_name(r->d.geometry),
        r->vtf ? "built and displaced in the vertex shader (vertex texture fetch, two loop frames "
                 "per pattern blended there)"
        : r->cpu_vterms ? "CPU-displaced (no vertex texture fetch) and the terms of each vertex "
                          "on the CPU (the driver refused the vertex shaders that evaluate "
                          "them), streamed per frame"
               : "CPU-displaced (no vertex texture fetch), streamed per frame",
        grid_vertex_count(r->grid), r->nfs,
        r->t->patterns - r->nfs, r->cpu_mask, r->cpu_mask | r->k_mask,
        r->gpu_blend ? "blended on the GPU from each table's two frames (stream_gpu.c; a "
                       "frame's chain uploaded when the phase reaches it)"
                     : "blended on the CPU and uploaded",
        r->gpu_blend ? "" : " (", r->gpu_blend ? "" : r->gpu_blend_why, r->gpu_blend ? "" : ")",
        blend_note,
        (unsigned long long)r->stream_bytes, r->nwc,
        r->run_lod ? "one level per run, by binding that level's own texture (software "
                     "rasteriser: per-pixel LOD is its slow path)"
                   : "per-pixel LOD",
        r->detile_refused ? "each pattern read once: it repeats on its tile (--detile auto: "
                            "the driver refused more programs with the random offsets)"
        : !renderer_detile(r) ? "each pattern read once: it repeats on its tile (--detile off; "
                                "auto in low quality)"
                            : "each pattern read at three random offsets blended over a lattice of "
                         "half-tiles (Heitz & Neyret 2018, detile.h)",
        r->gpu->caps.tier == TIER_GLES2_MIN ? "mediump (gles2-min)"
        : r->gpu->caps.prefer_highp ? "highp (software rasteriser: its mediump is emulated fp16)"
                                    : "mediump",
        r->sky_half ? "half-float radiances (RGBA16F)" : "RGBA8 with a scale",
        r->d.quality == QUALITY_HIGH
            ? r->run_lod
              ? "high: Ross BRDF sun (eq. 15), sky map filtered at one level per run of rows "
                "(eq. 27 for the run's mean variance; software rasteriser), effective Fresnel "
                "(eq. 26) on Hu's Fresnel texture, refraction (eq. 28), whitecaps (Dupuy eq. 6)"
            : shader_has_gradients(&r->gpu->caps)
              ? "high: Ross BRDF sun (eq. 15), sky map filtered with explicit gradients (eq. 27, "
                "textureGrad), effective Fresnel (eq. 26) on Hu's Fresnel texture, "
                "refraction (eq. 28), whitecaps (Dupuy eq. 6)"
              : "high: Ross BRDF sun (eq. 15), sky map filtered by an LOD bias beyond the pixel's "
                "own LOD, read from the map's alpha (eq. 27), effective Fresnel "
              "(eq. 26) on Hu's Fresnel texture, refraction (eq. 28), whitecaps (Dupuy eq. 6)"
            : "low: one pass with the same slope moments, Ross BRDF sun (eq. 15), effective "
              "Fresnel (eq. 26) and refraction (eq. 28); the sky filtered as high quality's "
              "(eq. 27) at the vertex's variance, whitecaps (Dupuy eq. 6) and haze per vertex");
    if (n > 0 && (size_t)n < size && !r->run_lod && !shader_has_gradients(&r->gpu->caps))
        n += snprintf(buf + n, size - (size_t)n, "sky LOD bias: at most %g (the device's "
                      "limit)\n", (double)r->gpu->caps.max_lod_bias);
    if (n > 0 && (size_t)n < size)
        snprintf(buf + n, size - (size_t)n, "programs: ocean k=K kw=KW %s%s (the start-up "
                 "probe's names), %d refused\n", render_quality_name(r->d.quality),
                 program_tags(r), r->refused);
}

/* After renderer_create gave rc: where the driver runs no ocean program of d's quality
 * (probe_programs), the same sea in the other rather than none (low's vertex shader carries
 * more of the shading, so either may be the one that fits). */
static int other_quality(int rc, struct renderer_desc *d, struct renderer **out,
                         void (*note)(void *user, const char *msg), void *user,
                         struct swell_err *err)
{
    if (rc != SWELL_E_SHADER)
        return rc;
    char msg[1400];
    int other = d->quality == QUALITY_HIGH ? QUALITY_LOW : QUALITY_HIGH;
    snprintf(msg, sizeof msg, "%s\n%s quality does not run on this GPU; trying quality %s",
             err ? err->msg : "", render_quality_name(d->quality), render_quality_name(other));
    if (note)
        note(user, msg);
    d->quality = other;
    return renderer_create(d, out, err);
}

int renderer_open(struct renderer_desc *d, struct gpu *gpu, int forced_tier, uint64_t budget,
                  void (*note)(void *user, const char *msg), void *user, struct renderer **out,
                  struct swell_err *err)
{
    char msg[1400];
    memset(gpu, 0, sizeof *gpu);
    if (gpu_init(gpu, forced_tier, budget, err))
        return err ? err->code : SWELL_E_GL;
    d->gpu = gpu;
    if (gpu->caps.tier_reason && note)
        note(user, gpu->caps.tier_reason);
    int rc = renderer_create(d, out, err);
    if (rc == SWELL_E_SHADER && forced_tier < 0 && gpu->caps.tier != TIER_GLES2_MIN) {
        /* the tier chosen runs none of this quality's programs (as VideoCore IV's gles2-ext
         * did, before gpu_default_tier kept vc4 on gles2-min: vc4 could not allocate registers
         * for the high-quality vertex shaders that fetch the displacement): the same quality
         * on gles2-min, whose vertex shaders are smaller (the CPU displaces the grid), before
         * the other quality */
        snprintf(msg, sizeof msg, "%s\n%s quality does not run on tier %s here; trying tier "
                 "gles2-min", err ? err->msg : "", render_quality_name(d->quality),
                 gpu_tier_name(gpu->caps.tier));
        if (note)
            note(user, msg);
        gpu_shutdown(gpu);
        memset(gpu, 0, sizeof *gpu);
        if (gpu_init(gpu, TIER_GLES2_MIN, budget, err))
            return err ? err->code : SWELL_E_GL;
        rc = renderer_create(d, out, err);
    }
    int asked = d->quality;
    rc = other_quality(rc, d, out, note, user, err);
    if (rc == SWELL_E_SHADER && (d->reflections || d->wakes || d->shadows || d->refractions ||
                                 d->wave_mask)) {
        /* no program with the objects' passes runs here (GC2000: over its 256 instructions):
         * the sea without them rather than none; the passes then say why they fail */
        snprintf(msg, sizeof msg, "%s\nthe ocean's programs with the objects' passes "
                 "(reflections, wakes, shadows, refractions, the wave mask) do not run on this "
                 "GPU; trying the sea without them", err ? err->msg : "");
        if (note)
            note(user, msg);
        d->reflections = d->wakes = d->shadows = d->refractions = d->wave_mask = 0;
        d->quality = asked;
        rc = other_quality(renderer_create(d, out, err), d, out, note, user, err);
        if (!rc)
            (*out)->objects_refused = 1;
    }
    if (rc)
        gpu_shutdown(gpu);
    return rc;
}

int renderer_objects(const struct renderer *r)
{
    return r->d.reflections || r->d.wakes || r->d.shadows || r->d.refractions ||
           r->d.wave_mask;
}

int renderer_objects_refused(const struct renderer *r, const char *what, struct swell_err *err)
{
    return swell_fail(err, SWELL_E_ARG, "renderer: no %s: this GPU's driver refused every ocean "
                      "program with the objects' passes, so the sea is drawn without "
                      "reflections, wakes, shadows, refractions and the wave mask (its messages "
                      "were at creation)", what);
}
