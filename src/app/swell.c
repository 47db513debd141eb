/* swell - render the ocean: fullscreen on a KMS display, or offscreen (EGL surfaceless) to PNG.
 *
 * main is a straight line: options -> tables (load, or bake in memory) -> platform -> gpu ->
 * renderer -> frame loop -> PNG output or present (or, with --bench, bench.c's timed frames
 * against the baseline quad -> summary and --results JSON) -> teardown in reverse. Library code
 * returns errors; only this file prints and exits (0 ok, 1 runtime failure, 2 usage error).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bake/bake.h"
#include "app/bench.h"
#include "app/boat.h"
#include "app/options.h"
#include "core/camera.h"
#include "gl/gpu.h"
#include "core/image.h"
#include "platform/input.h"
#include "platform/platform.h"
#include "core/preset.h"
#include "geometry/kelvin.h"
#include "render/renderer.h"
#include "tables/tables_io.h"
#include "render/upscale.h"

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* On KMS the frame rate every FPS_REPORT_S of wall time, as kmscube does: frames presented
 * over the time they took, and the mean time per frame. */
#define FPS_REPORT_S 2.0
struct fps_meter {
    double t0;          /* start of the interval, s */
    int frames;         /* presented in it */
};

static void fps_tick(struct fps_meter *m, double now)
{
    m->frames++;
    double dt = now - m->t0;
    if (dt < FPS_REPORT_S)
        return;
    printf("swell: %.1f fps (%.1f ms per frame) over %.1f s\n", m->frames / dt,
           1e3 * dt / m->frames, dt);
    fflush(stdout);
    m->t0 = now;
    m->frames = 0;
}

/* renderer_open's fallbacks, told on stderr (what was refused and what is tried instead). */
static void note_fallback(void *user, const char *msg)
{
    const char *p = msg;
    while (*p) {
        const char *nl = strchr(p, '\n');
        int n = nl ? (int)(nl - p) : (int)strlen(p);
        fprintf(stderr, "swell: %.*s\n", n, p);
        p += n + (nl ? 1 : 0);
    }
}

static int load_tables(struct options *o, struct swell_tables *t, struct swell_err *err)
{
    if (o->tables_dir) {
        int rc = tables_load_dir_within(o->tables_dir, o->budget, t, err);
        if (rc)
            return swell_err_context(err, "loading --tables %s", o->tables_dir);
        return SWELL_OK;
    }
    if (o->budget)
        o->state.budget_bytes = o->budget;
    int rc = swell_bake(&o->state, NULL, t, err);
    if (rc)
        return swell_err_context(err, "baking the sea state in memory");
    return SWELL_OK;
}

/* --debug variants: the frame's share of the screen per ocean program (renderer.h
 * renderer_pixel_variant), in the probe's names, on one line. */
static void print_variant_shares(const struct renderer *r, int frame, const uint8_t *rgba, int w,
                                 int h)
{
    enum { NV = RENDERER_OCEAN_VARIANTS };
    size_t count[NV + 2] = { 0 }, n = (size_t)w * (size_t)h;
    for (size_t i = 0; i < n; i++) {
        int v = renderer_pixel_variant(rgba + 4 * i);
        count[v == RENDERER_PIXEL_SKY ? NV : v == RENDERER_PIXEL_MIXED ? NV + 1 : v]++;
    }
    printf("swell: frame %d: screen share: sky %.4f", frame, (double)count[NV] / (double)n);
    for (int v = 0; v < NV; v++)
        if (count[v]) {
            char name[64];
            renderer_program_name(r, v, name, sizeof name);
            printf("; %s %.4f", name, (double)count[v] / (double)n);
        }
    printf("; mixed %.4f\n", (double)count[NV + 1] / (double)n);
}

/* Frame loop: everything it needs exists already; it allocates nothing but the PNG path. */
/* The sun's direction, world (towards it). */
static void sun_direction(float elev_deg, float azim_deg, float out[3])
{
    double e = elev_deg * M_PI / 180.0, a = azim_deg * M_PI / 180.0;
    out[0] = (float)(cos(e) * cos(a));
    out[1] = (float)(cos(e) * sin(a));
    out[2] = (float)sin(e);
}

/* The demo boat in a frame (--boat): before the sea, its pose on the sea at t, its wake (none
 * below the slowest speed a wake is drawn for), its reflection, shadow and refraction passes
 * (the renderer reads them); after the sea, the boat itself, depth-tested. bench.h's hooks take the
 * same. */
struct boat_scene {
    struct renderer *r;
    struct boat *boat;
    const struct swell_tables *tables;
    float sun_elev_deg, sun_azim_deg;
    struct renderer_view view;        /* the frame's (boat_before) */
};

static int boat_before(void *ctx, const struct camera *cam, double t, int w, int h,
                       struct swell_err *err)
{
    struct boat_scene *bs = ctx;
    struct renderer *r = bs->r;
    struct boat *b = bs->boat;
    float sun_dir[3];
    sun_direction(bs->sun_elev_deg, bs->sun_azim_deg, sun_dir);
    renderer_frame_view(r, cam, w, h, &bs->view);
    boat_pose_at(b, bs->tables, renderer_detile(r), t);
    if (!renderer_objects(r))
        return 0;   /* the driver runs no program with the passes: the boat on the bare sea */
    const struct boat_pose *p = boat_pose(b);
    const struct boat_desc *bd = boat_get_desc(b);
    struct renderer_wake wk = {
        .pos = { p->pos[0], p->pos[1] }, .heading_deg = bd->heading_deg,
        .speed_mps = bd->speed_mps, .hull_length_m = BOAT_LENGTH_M, .beam_m = BOAT_BEAM_M,
    };
    int rc = renderer_set_wake(r, bd->speed_mps >= KELVIN_MIN_SPEED_MPS ? &wk : NULL, err);
    if (rc)
        return rc;
    const struct renderer_view *v = &bs->view;
    double dx = p->pos[0] - v->cam.pos[0], dy = p->pos[1] - v->cam.pos[1];
    struct renderer_reflection rr = { .distance_m = (float)sqrt(dx * dx + dy * dy) };
    struct renderer_pass pass;
    if ((rc = renderer_reflection_begin(r, v, &rr, &pass, err)))
        return rc;
    glEnable(GL_DEPTH_TEST);
    boat_draw(b, pass.view, pass.proj, pass.camera_pos, sun_dir, 0.0f);
    if ((rc = renderer_reflection_end(r, err)))
        return rc;
    struct renderer_shadow sh = { .distance_m = (float)fmax(2.0 * rr.distance_m, 60.0) };
    if ((rc = renderer_shadow_begin(r, v, &sh, &pass, err)))
        return rc;
    boat_draw(b, pass.view, pass.proj, pass.camera_pos, sun_dir, 0.0f);
    if ((rc = renderer_shadow_end(r, err)))
        return rc;
    /* its hull under the water, seen through it */
    struct renderer_refraction rf = { .depth_m = 0.5f, .distance_m = rr.distance_m };
    if ((rc = renderer_refraction_begin(r, v, &rf, &pass, err)))
        return rc;
    boat_draw(b, pass.view, pass.proj, pass.camera_pos, sun_dir, pass.attenuation_per_m);
    return renderer_refraction_end(r, err);
}

static int boat_after(void *ctx, const struct camera *cam, double t, int w, int h,
                      struct swell_err *err)
{
    (void)t;
    (void)err;
    struct boat_scene *bs = ctx;
    struct camera_frame cf;
    float sun_dir[3];
    sun_direction(bs->sun_elev_deg, bs->sun_azim_deg, sun_dir);
    camera_frame_make(&bs->view.cam, w, h, &cf);
    boat_draw(bs->boat, (const float *)cf.view_rel, (const float *)cf.proj, cam->pos, sun_dir,
              0.0f);
    return SWELL_OK;
}

static int run_frames(const struct options *o, struct platform_handle *ph, struct renderer *r,
                      struct upscale *up, int is_kms, const struct swell_tables *tables,
                      struct boat *boat, struct swell_err *err)
{
    int w = 0, h = 0;
    ph->be->size(ph->p, &w, &h);
    float fov = o->camera.fov_y_deg > 0.0f ? o->camera.fov_y_deg : CAMERA_FOV_DEFAULT_DEG;
    float fov_drawn = camera_fov_covered(fov, h > 0 ? (float)w / (float)h : 1.0f);
    if (fov_drawn < fov)
        printf("swell: %dx%d is wider than the sea's grid covers at a %.0f deg vertical field of "
               "view (a half diagonal of at most %.0f deg): drawn at %.1f deg\n", w, h,
               (double)fov, CAMERA_HALF_DIAGONAL_MAX_DEG, (double)fov_drawn);
    int frames = o->frames;
    if (frames < 0) {
        double fps = o->fps > 0 ? o->fps : DEFAULT_FPS;
        frames = o->duration_s > 0 ? (int)ceil(o->duration_s * fps) : (is_kms ? 0 : 1);
    }
    if (frames == 0 && !is_kms && o->duration_s <= 0)
        return swell_fail(err, SWELL_E_ARG, "--frames 0 renders until quit, which never comes "
                          "offscreen; give --frames N or --duration S");
    if (o->out && options_out_conversions(o->out) == 0 && frames != 1)
        return swell_fail(err, SWELL_E_ARG, "--out: '%s' has no %%d pattern but %s frames are "
                          "rendered (e.g. out/frame%%04d.png)", o->out,
                          frames ? "several" : "unlimited");
    uint8_t *rgba = NULL;
    if (o->out || is_kms || o->debug_variants) {   /* KMS: screenshots on a key press; never
                                                    * allocate per frame */
        rgba = malloc((size_t)w * (size_t)h * 4);
        if (!rgba)
            return swell_fail(err, SWELL_E_NOMEM, "no memory for a %dx%d read-back", w, h);
    }
    /* Keyboard on KMS (libinput); with no input devices it is simply inactive. */
    struct input *in = NULL;
    struct input_state keys;
    input_state_init(&keys);
    if (is_kms) {
        struct input_desc idesc = { 0 };
        char line[256];
        int irc = input_create(&idesc, &in, err);
        if (irc) {
            free(rgba);
            return irc;
        }
        input_describe(in, line, sizeof line);
        printf("swell: %s\n", line);
    }
    /* On KMS without --fps the animation follows the clock; otherwise it steps exactly. */
    int wall_clock = is_kms && o->fps <= 0;
    double step = 1.0 / (o->fps > 0 ? o->fps : DEFAULT_FPS);
    double start = now_s(), prev = start;
    struct fps_meter fps = { start, 0 };
    struct camera live = o->camera;     /* moved by the keyboard when no --path is given */
    /* 0 means the renderer's default elevation (renderer.h) */
    float sun = o->sun_elev_deg > 0.0f ? o->sun_elev_deg : 30.0f;
    int shots = 0, boat_shown = boat != NULL;
    int rc = SWELL_OK;
    for (int i = 0; frames == 0 || i < frames; i++) {
        double t = wall_clock ? o->time0_s + (now_s() - start) : o->time0_s + i * step;
        if (o->duration_s > 0 && t - o->time0_s >= o->duration_s)
            break;
        if (ph->be->should_quit(ph->p))
            break;
        double now = now_s();
        input_poll(in, &keys);
        if (keys.quit)
            break;
        input_camera_step(&keys, now - prev, &live);
        int sun_keys = input_held(&keys, INPUT_HOLD_SUN_UP) ||
                       input_held(&keys, INPUT_HOLD_SUN_DOWN);
        float sun_now = sun_keys ? input_sun_step(&keys, now - prev, sun) : sun;
        prev = now;
        if (sun_now != sun) {
            sun = sun_now;
            if ((rc = renderer_set_sun(r, sun, o->sun_azim_deg, err)))
                break;
        }
        if (keys.preset != INPUT_PRESET_NONE)
            printf("swell: preset %s requested: restart with --preset %s (tables are not "
                   "re-baked while running)\n", input_preset_name(keys.preset),
                   input_preset_name(keys.preset));
        if (keys.boat && boat) {
            boat_shown = !boat_shown;
            printf("swell: boat %s\n", boat_shown ? "shown" : "hidden");
            if (!boat_shown && renderer_objects(r) && (rc = renderer_set_wake(r, NULL, err)))
                break;
        }
        struct camera cam = live;
        if (o->path > CAMERA_PATH_NONE)
            camera_path_at(o->path, t, &cam);
        int fw = up ? up->w : w, fh = up ? up->h : h;
        rc = ph->be->begin_frame(ph->p, err);
        if (!rc && up)
            upscale_begin(up);
        struct boat_scene bs = { .r = r, .boat = boat, .tables = tables, .sun_elev_deg = sun,
                                 .sun_azim_deg = o->sun_azim_deg };
        if (!rc && boat && boat_shown)
            rc = boat_before(&bs, &cam, t, fw, fh, err);
        if (!rc)
            rc = renderer_frame(r, &cam, t, fw, fh, err);
        if (!rc && boat && boat_shown) {
            rc = boat_after(&bs, &cam, t, fw, fh, err);
            if (o->verbose) {
                const struct boat_pose *bp = boat_pose(boat);
                printf("swell: frame %d: boat at (%.1f, %.1f), heave %.2f m, pitch %.1f deg, "
                       "roll %.1f deg\n", i, bp->pos[0], bp->pos[1], bp->pos[2],
                       (double)bp->pitch_deg, (double)bp->roll_deg);
            }
        }
        if (!rc && up)
            rc = upscale_end(up, err);
        if (!rc)
            rc = ph->be->present(ph->p, err);
        if (!rc && is_kms)
            fps_tick(&fps, now_s());
        if (!rc && o->verbose) {
            struct renderer_stats st;
            renderer_get_stats(r, &st);
            if (st.camera_raise_m > 0.0)
                printf("swell: frame %d: camera drawn %.2f m higher, %.1f m above the sea "
                       "surface under it\n", i, st.camera_raise_m, (double)CAMERA_CLEARANCE_M);
        }
        if (!rc && o->debug_variants && !(rc = ph->be->read_rgba(ph->p, rgba, err)))
            print_variant_shares(r, i, rgba, w, h);
        if (!rc && o->out) {
            char path[MAX_PATH_LEN];
            snprintf(path, sizeof path, o->out, i);
            if (!o->debug_variants)   /* else read above */
                rc = ph->be->read_rgba(ph->p, rgba, err);
            if (!rc)
                rc = image_write_png(path, rgba, w, h, err);
            if (!rc && o->verbose)
                printf("swell: frame %d t=%.3f s -> %s\n", i, t, path);
        }
        if (!rc && keys.screenshot) {
            char path[64];
            snprintf(path, sizeof path, "swell-shot-%04d.png", shots++);
            rc = ph->be->read_rgba(ph->p, rgba, err);
            if (!rc)
                rc = image_write_png(path, rgba, w, h, err);
            if (!rc)
                printf("swell: screenshot %s\n", path);
        }
        if (rc) {
            swell_err_context(err, "frame %d (t = %.3f s)", i, t);
            break;
        }
    }
    input_destroy(in);
    free(rgba);
    return rc;
}

/* --bench: bench.c runs the frames (with the boat's work in each, --boat); this prints the
 * one-line summary and writes --results. */
static int run_bench(const struct options *o, struct platform_handle *ph, struct gpu *g,
                     struct renderer *r, struct upscale *up, const struct swell_tables *tables,
                     struct boat *boat, struct swell_err *err)
{
    struct boat_scene bs = { .r = r, .boat = boat, .tables = tables,
                             .sun_elev_deg = o->sun_elev_deg > 0.0f ? o->sun_elev_deg : 30.0f,
                             .sun_azim_deg = o->sun_azim_deg };
    struct bench_desc bd = {
        .ph = ph, .renderer = r, .gpu = g, .upscale = up, .camera = o->camera, .path = o->path,
        .time0_s = o->time0_s, .step_s = 1.0 / (o->fps > 0 ? o->fps : DEFAULT_FPS),
        .warmup = o->warmup < 0 ? 0 : o->warmup == 0 ? -1 : o->warmup,
        .frames = o->frames > 0 ? o->frames : 0,
        .scene = o->scene ? o->scene : o->tables_dir ? o->tables_dir : "baked in memory",
        .quality = render_quality_name(o->quality), .geometry = geometry_kind_name(o->geometry),
        .detile = renderer_detile(r) ? "on" : "off",
        .before = boat ? boat_before : NULL, .after = boat ? boat_after : NULL, .ctx = &bs,
    };
    struct bench_result res;
    int rc = bench_run(&bd, &res, err);
    if (rc)
        return rc;
    char line[512];
    bench_format_summary(&res, line, sizeof line);
    printf("swell: %s\n", line);
    if (!res.cpu_valid)
        printf("swell: bench: %s\n", res.notes);
    if (o->results) {
        rc = bench_write_json(o->results, &res, err);
        if (!rc)
            printf("swell: bench: results in %s\n", o->results);
    }
    fflush(stdout);
    return rc;
}

static void print_start(const struct options *o, const struct platform_handle *ph,
                        const struct gpu *g, const struct swell_tables *t, struct renderer *r,
                        const struct upscale *up)
{
    int w = 0, h = 0;
    ph->be->size(ph->p, &w, &h);
    printf("swell: platform %s, %dx%d\n", ph->be->name, w, h);
    if (up)
        printf("swell: render scale %.2f: the frame drawn at %dx%d, stretched over %dx%d\n",
               o->scale, up->w, up->h, w, h);
    printf("swell: GL %s | %s | %s\n", g->caps.vendor, g->caps.renderer, g->caps.version);
    printf("swell: tier %s (available %s%s)\n", gpu_tier_name(g->caps.tier),
           gpu_tier_name(g->caps.tier_available), o->tier >= 0 ? ", forced" : "");
    printf("swell: tables %s: %d patterns, %d frames over %.1f s, Hs %.2f m, wind %.1f m/s\n",
           o->tables_dir ? o->tables_dir : "(baked in memory)", t->patterns, t->frames,
           t->loop_period_s, t->hs_m, t->state.wind_speed_mps);
    char desc[2048];
    renderer_describe(r, desc, sizeof desc);
    printf("%s%s", desc, desc[0] && desc[strlen(desc) - 1] != '\n' ? "\n" : "");
    struct renderer_stats st;
    renderer_get_stats(r, &st);
    printf("swell: GPU memory %.2f MiB of %.2f MiB budget (renderer %.2f MiB), %d vertices, "
           "%d triangles, %.1f KiB streamed per frame\n", g->bytes / 1048576.0,
           g->budget_bytes / 1048576.0, st.gpu_bytes / 1048576.0, st.vertices, st.triangles,
           st.cpu_bytes_per_frame / 1024.0);
    /* The display's frame (tables/budget.h: not the sea's, not charged): one colour buffer
     * offscreen, at least two for KMS page flips, and the depth buffer. */
    GLint depth_bits = 0;
    glGetIntegerv(GL_DEPTH_BITS, &depth_bits);
    int buffers = strcmp(ph->be->name, "kms") == 0 ? 2 : 1;
    double fb = (double)w * (double)h * (4.0 * buffers + (double)((depth_bits + 7) / 8));
    printf("swell: frame buffers %.2f MiB (%d colour at %dx%d and %d-bit depth: the display's, "
           "not in the sea's budget)\n", fb / 1048576.0, buffers, w, h, (int)depth_bits);
    fflush(stdout);
}

int main(int argc, char **argv)
{
    struct options o;
    memset(&o, 0, sizeof o);
    o.frames = -1;
    o.warmup = -1;
    o.tier = -1;
    camera_defaults(&o.camera);
    int rc = options_parse(argc, argv, &o);
    if (rc)
        return rc;
    if (!o.tables_dir && !o.baking)
        o.baking = 1;   /* default sea state, baked in memory */

    struct swell_err err = { 0 };
    struct swell_tables tables;
    memset(&tables, 0, sizeof tables);
    struct platform_handle ph = { 0 };
    struct gpu gpu;
    memset(&gpu, 0, sizeof gpu);
    struct renderer *r = NULL;
    int status = 1;

    if (load_tables(&o, &tables, &err))
        goto fail;
    /* A GLES 3 context unless a lower tier is forced (then GLES 2, as such a device has). */
    o.platform.gles_major = (o.tier < 0 || o.tier == TIER_GLES3) ? 3 : 2;
    if (platform_open(&o.platform, &ph, &err))
        goto fail_tables;
    uint64_t budget = o.budget ? o.budget : tables.state.budget_bytes;
    struct renderer_desc rd = {
        .tables = &tables, .quality = o.quality, .geometry = o.geometry,
        .sun_elev_deg = o.sun_elev_deg, .sun_azim_deg = o.sun_azim_deg,
        .pixel_lod = o.pixel_lod, .debug_uncovered = o.debug_uncovered,
        .debug_variants = o.debug_variants,
        .detile = o.detile, .reflections = o.boat, .wakes = o.boat, .shadows = o.boat,
        .refractions = o.boat,
    };
    rc = renderer_open(&rd, &gpu, o.tier, budget, note_fallback, NULL, &r, &err);
    o.quality = rd.quality;
    if (rc)
        goto fail_platform;
    struct upscale up_store, *up = NULL;
    if (o.scale > 0 && o.scale < 1) {
        /* the output's framebuffer is bound here (the platform's; the probe restored it) */
        int w = 0, h = 0;
        GLint depth_bits = 0;
        ph.be->size(ph.p, &w, &h);
        glGetIntegerv(GL_DEPTH_BITS, &depth_bits);
        if (upscale_create(&up_store, &gpu, w, h, o.scale, depth_bits, NULL, &err))
            goto fail_renderer;
        up = &up_store;
    }
    struct boat *boat = NULL;
    if (o.boat) {
        /* 30 m ahead of the first frame's camera */
        struct camera c0 = o.camera;
        if (o.path > CAMERA_PATH_NONE)
            camera_path_at(o.path, o.time0_s, &c0);
        double hd = c0.heading_deg * M_PI / 180.0;
        struct boat_desc bd = {
            .x0 = c0.pos[0] + 30.0 * cos(hd), .y0 = c0.pos[1] + 30.0 * sin(hd),
            .t0_s = o.time0_s, .heading_deg = o.boat_heading_deg,
            .speed_mps = o.boat_speed_mps,
        };
        if (boat_create(&bd, NULL, &gpu.caps, &boat, &err))
            goto fail_upscale;
    }
    print_start(&o, &ph, &gpu, &tables, r, up);
    if (o.bench ? run_bench(&o, &ph, &gpu, r, up, &tables, boat, &err)
                : run_frames(&o, &ph, r, up, ph.be == &platform_kms_backend, &tables, boat,
                             &err))
        goto fail_boat;
    status = 0;

fail_boat:
    boat_destroy(boat);
fail_upscale:
    if (up)
        upscale_destroy(up);
fail_renderer:
    renderer_destroy(r);
    gpu_shutdown(&gpu);
fail_platform:
    platform_close(&ph);
fail_tables:
    tables_destroy(&tables);
fail:
    if (status)
        fprintf(stderr, "swell: %s (%s)\n", err.msg, swell_err_name(err.code));
    return status;
}
