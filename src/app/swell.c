/* swell - render the ocean: fullscreen on a KMS display, or offscreen (EGL surfaceless) to PNG.
 *
 * main is a straight line: options -> sea (swell_sea_load, or swell_sea_bake in memory) ->
 * platform -> ocean (swell_ocean_create) -> frame loop -> PNG output or present (or, with
 * --bench, bench.c's timed frames against the baseline quad -> summary and --results JSON) ->
 * teardown in reverse. The sea is reached through swell.h alone, as an embedding application
 * reaches it: this program makes its own camera matrices (core/camera.h), its own context and
 * display (platform/), its own objects (the demo boat) and its own PNGs. Only this file prints
 * and exits (0 ok, 1 runtime failure, 2 usage error).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <GLES2/gl2.h>

#include "swell.h"
#include "app/bench.h"
#include "app/boat.h"
#include "app/glapp.h"
#include "app/options.h"
#include "core/camera.h"
#include "core/err.h"
#include "core/image.h"
#include "platform/input.h"
#include "platform/platform.h"

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

/* swell_ocean_create's fallbacks, told on stderr (what was refused and what is tried instead). */
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

/* The program's state: the sea and ocean (swell.h), the platform, the render scale, the boat. */
struct app {
    const struct options *o;
    struct platform_handle *ph;
    swell_sea *sea;
    swell_ocean *ocean;
    swell_upscale *up;              /* --scale below 1; NULL otherwise */
    struct boat *boat;              /* --boat; NULL otherwise */
    swell_ocean_stats st;           /* after create: tier, quality, detile, objects */
    int out_w, out_h;               /* the platform's frame */
    int boat_shown;
    float sun_elev_deg, sun_azim_deg;
    double raise_m;                 /* the last frame drew the camera this much higher */
};

static int load_sea(const struct options *o, swell_sea **sea, struct swell_err *err)
{
    if (o->tables_dir) {
        if (swell_sea_load_budget(o->tables_dir, o->budget, sea, err))
            return swell_err_context(err, "loading --tables %s", o->tables_dir);
        return SWELL_OK;
    }
    swell_sea_desc d = { .options = o->sea_count ? o->sea : NULL, .budget_bytes = o->budget };
    if (swell_sea_bake(&d, sea, err))
        return swell_err_context(err, "baking the sea state in memory");
    return SWELL_OK;
}

/* --debug variants: the frame's share of the screen per ocean program
 * (swell_ocean_program_at), in the probe's names, on one line. */
#define SHARES_MAX 64
static void print_variant_shares(const swell_ocean *ocean, int frame, const uint8_t *rgba,
                                 int w, int h)
{
    size_t count[SHARES_MAX] = { 0 }, sky = 0, mixed = 0, n = (size_t)w * (size_t)h;
    char names[SHARES_MAX][64];
    for (size_t i = 0; i < n; i++) {
        char name[64];
        int v = swell_ocean_program_at(ocean, rgba + 4 * i, name, sizeof name);
        if (v == SWELL_PIXEL_SKY) {
            sky++;
        } else if (v < 0 || v >= SHARES_MAX) {
            mixed++;
        } else {
            if (!count[v]++)
                snprintf(names[v], sizeof names[v], "%s", name);
        }
    }
    printf("swell: frame %d: screen share: sky %.4f", frame, (double)sky / (double)n);
    for (int v = 0; v < SHARES_MAX; v++)
        if (count[v])
            printf("; %s %.4f", names[v], (double)count[v] / (double)n);
    printf("; mixed %.4f\n", (double)mixed / (double)n);
}

/* The sun's direction, world (towards it). */
static void sun_direction(float elev_deg, float azim_deg, float out[3])
{
    double e = elev_deg * M_PI / 180.0, a = azim_deg * M_PI / 180.0;
    out[0] = (float)(cos(e) * cos(a));
    out[1] = (float)(cos(e) * sin(a));
    out[2] = (float)sin(e);
}

/* The view of camera cam at t into a w x h frame, as an application makes it: the field of
 * view narrowed to what the sea's grid covers (camera_fov_covered), the camera kept
 * CAMERA_CLEARANCE_M above the water under it (swell_sea_sample, as the ocean reads it), the
 * clip planes from its height above that water, the matrices by core/camera.h. */
static int make_view(struct app *app, const struct camera *cam, double t, int w, int h,
                     swell_view *v, struct swell_err *err)
{
    struct camera c = *cam;
    c.fov_y_deg = camera_fov_covered(cam->fov_y_deg, h > 0 ? (float)w / (float)h : 1.0f);
    swell_sample_desc sd = { .no_detile = !app->st.detile, .height_only = 1 };
    swell_sample s;
    int rc = swell_sea_sample(app->sea, &sd, c.pos, 1, t, &s, err);
    if (rc)
        return rc;
    c.surface_z_m = s.height_m;
    app->raise_m = 0.0;
    if (c.pos[2] < c.surface_z_m + CAMERA_CLEARANCE_M) {
        app->raise_m = c.surface_z_m + CAMERA_CLEARANCE_M - c.pos[2];
        c.pos[2] = c.surface_z_m + CAMERA_CLEARANCE_M;
    }
    struct camera_frame cf;
    camera_frame_make(&c, w, h, &cf);
    memset(v, 0, sizeof *v);
    memcpy(v->camera_pos, c.pos, sizeof v->camera_pos);
    memcpy(v->view, cf.view_rel, sizeof v->view);
    memcpy(v->proj, cf.proj, sizeof v->proj);
    v->viewport[2] = w;
    v->viewport[3] = h;
    /* --debug uncovered clears to magenta itself (draw_frame) */
    v->flags = (app->o->debug_uncovered ? 0u : (unsigned)SWELL_DRAW_CLEAR) | SWELL_DRAW_SKY;
    return SWELL_OK;
}

/* The demo boat (--boat) before the sea: its pose on the sea at t, its wake (none below the
 * slowest speed a wake is drawn for), its reflection, shadow and refraction passes (the
 * ocean reads them). */
static int boat_before(struct app *app, const swell_view *v, double t, struct swell_err *err)
{
    struct boat *b = app->boat;
    float sun_dir[3];
    sun_direction(app->sun_elev_deg, app->sun_azim_deg, sun_dir);
    int rc = boat_pose_at(b, app->sea, app->st.detile, t, err);
    if (rc || !app->st.objects)
        return rc;  /* the driver runs no program with the passes: the boat on the bare sea */
    const struct boat_pose *p = boat_pose(b);
    const struct boat_desc *bd = boat_get_desc(b);
    swell_wake wk = {
        .position_m = { p->pos[0], p->pos[1] }, .heading_deg = bd->heading_deg,
        .speed_mps = bd->speed_mps, .hull_length_m = BOAT_LENGTH_M, .beam_m = BOAT_BEAM_M,
    };
    rc = swell_ocean_set_wake(app->ocean, bd->speed_mps >= SWELL_WAKE_SPEED_MIN_MPS ? &wk : NULL,
                              err);
    if (rc)
        return rc;
    double dx = p->pos[0] - v->camera_pos[0], dy = p->pos[1] - v->camera_pos[1];
    swell_reflection_desc rd = { .object_distance_m = (float)sqrt(dx * dx + dy * dy) };
    swell_pass pass;
    if ((rc = swell_ocean_begin_reflection(app->ocean, v, &rd, &pass, err)))
        return rc;
    glEnable(GL_DEPTH_TEST);
    boat_draw(b, pass.view, pass.proj, pass.camera_pos, sun_dir, 0.0f);
    if ((rc = swell_ocean_end_reflection(app->ocean, err)))
        return rc;
    swell_shadow_desc sh = { .distance_m = (float)fmax(2.0 * rd.object_distance_m, 60.0) };
    if ((rc = swell_ocean_begin_shadow(app->ocean, v, &sh, &pass, err)))
        return rc;
    boat_draw(b, pass.view, pass.proj, pass.camera_pos, sun_dir, 0.0f);
    if ((rc = swell_ocean_end_shadow(app->ocean, err)))
        return rc;
    /* its hull under the water, seen through it */
    swell_refraction_desc rf = { .object_depth_m = 0.5f,
                                 .object_distance_m = rd.object_distance_m };
    if ((rc = swell_ocean_begin_refraction(app->ocean, v, &rf, &pass, err)))
        return rc;
    boat_draw(b, pass.view, pass.proj, pass.camera_pos, sun_dir, pass.attenuation_per_m);
    return swell_ocean_end_refraction(app->ocean, err);
}

/* One frame into the bound framebuffer: (the render scale's target,) the boat's passes, the
 * sea, the boat depth-tested against it, (the stretch). bench.c times the same. */
static int draw_frame(struct app *app, const struct camera *cam, double t,
                      struct swell_err *err)
{
    int w = app->out_w, h = app->out_h, rc;
    if (app->up) {
        swell_upscale_begin(app->up);
        swell_upscale_size(app->up, &w, &h);
    }
    swell_view v;
    rc = make_view(app, cam, t, w, h, &v, err);
    int boat = app->boat && app->boat_shown;
    if (!rc && boat)
        rc = boat_before(app, &v, t, err);
    if (!rc && app->o->debug_uncovered) {
        /* magenta: a pixel neither the sky nor the sea covers shows */
        glViewport(0, 0, w, h);
        glClearColor(1.0f, 0.0f, 1.0f, 1.0f);
        glDepthMask(GL_TRUE);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    }
    if (!rc)
        rc = swell_ocean_draw(app->ocean, &v, t, err);
    if (!rc && boat) {
        float sun_dir[3];
        sun_direction(app->sun_elev_deg, app->sun_azim_deg, sun_dir);
        boat_draw(app->boat, v.view, v.proj, v.camera_pos, sun_dir, 0.0f);
    }
    if (!rc && app->up)
        rc = swell_upscale_end(app->up, err);
    return rc;
}

static int run_frames(struct app *app, int is_kms, struct swell_err *err)
{
    const struct options *o = app->o;
    struct platform_handle *ph = app->ph;
    int w = app->out_w, h = app->out_h;
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
    int shots = 0;
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
        float sun = app->sun_elev_deg;
        float sun_now = sun_keys ? input_sun_step(&keys, now - prev, sun) : sun;
        prev = now;
        if (sun_now != sun) {
            app->sun_elev_deg = sun_now;
            if ((rc = swell_ocean_set_sun(app->ocean, sun_now, app->sun_azim_deg, err)))
                break;
        }
        if (keys.preset != INPUT_PRESET_NONE)
            printf("swell: preset %s requested: restart with --preset %s (tables are not "
                   "re-baked while running)\n", input_preset_name(keys.preset),
                   input_preset_name(keys.preset));
        if (keys.boat && app->boat) {
            app->boat_shown = !app->boat_shown;
            printf("swell: boat %s\n", app->boat_shown ? "shown" : "hidden");
            if (!app->boat_shown && app->st.objects &&
                (rc = swell_ocean_set_wake(app->ocean, NULL, err)))
                break;
        }
        struct camera cam = live;
        if (o->path > CAMERA_PATH_NONE)
            camera_path_at(o->path, t, &cam);
        rc = ph->be->begin_frame(ph->p, err);
        if (!rc)
            rc = draw_frame(app, &cam, t, err);
        if (!rc && app->boat && app->boat_shown && o->verbose) {
            const struct boat_pose *bp = boat_pose(app->boat);
            printf("swell: frame %d: boat at (%.1f, %.1f), heave %.2f m, pitch %.1f deg, "
                   "roll %.1f deg\n", i, bp->pos[0], bp->pos[1], bp->pos[2],
                   (double)bp->pitch_deg, (double)bp->roll_deg);
        }
        if (!rc)
            rc = ph->be->present(ph->p, err);
        if (!rc && is_kms)
            fps_tick(&fps, now_s());
        if (!rc && o->verbose && app->raise_m > 0.0)
            printf("swell: frame %d: camera drawn %.2f m higher, %.1f m above the sea "
                   "surface under it\n", i, app->raise_m, (double)CAMERA_CLEARANCE_M);
        if (!rc && o->debug_variants && !(rc = ph->be->read_rgba(ph->p, rgba, err)))
            print_variant_shares(app->ocean, i, rgba, w, h);
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

static int bench_frame(void *ctx, const struct camera *cam, double t, struct swell_err *err)
{
    return draw_frame(ctx, cam, t, err);
}

/* --bench: bench.c runs the frames (with the boat's work in each, --boat); this prints the
 * one-line summary and writes --results. */
static int run_bench(struct app *app, struct swell_err *err)
{
    const struct options *o = app->o;
    struct bench_desc bd = {
        .ph = app->ph, .frame = bench_frame, .ctx = app, .camera = o->camera, .path = o->path,
        .time0_s = o->time0_s, .step_s = 1.0 / (o->fps > 0 ? o->fps : DEFAULT_FPS),
        .warmup = o->warmup < 0 ? 0 : o->warmup == 0 ? -1 : o->warmup,
        .frames = o->frames > 0 ? o->frames : 0, .swell_tier = app->st.tier,
        .scale = app->up ? o->scale : 1.0,
        .scene = o->scene ? o->scene : o->tables_dir ? o->tables_dir : "baked in memory",
        .quality = options_quality_name(app->st.quality),
        .geometry = options_geometry_name(o->geometry),
        .detile = app->st.detile ? "on" : "off",
        .cpu_scope = app->boat
            ? "the frame and the application's work around it (the boat's pose, wake, "
              "reflection, shadow and refraction passes and draw) on the calling thread, with "
              "the GL calls (on a software GL the driver's vertex processing runs here too)"
            : "the frame on the calling thread: the view, grid projection and displacement, "
              "loop-frame blending and the GL calls (on a software GL the driver's vertex "
              "processing runs here too)",
    };
    struct bench_result res;
    int rc = bench_run(&bd, &res, err);
    if (rc)
        return rc;
    swell_ocean_stats st;
    swell_ocean_get_stats(app->ocean, &st);
    res.bytes_gpu = st.gpu_bytes;
    res.budget_bytes = st.budget_bytes;
    res.bytes_streamed_per_frame = st.cpu_bytes_per_frame;
    res.vertices = st.vertices;
    res.triangles = st.triangles;
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

static const char *gl_string(GLenum name)
{
    const char *s = (const char *)glGetString(name);
    return s ? s : "?";
}

static void print_start(const struct app *app)
{
    const struct options *o = app->o;
    int w = app->out_w, h = app->out_h;
    printf("swell: platform %s, %dx%d\n", app->ph->be->name, w, h);
    if (app->up) {
        int uw, uh;
        swell_upscale_size(app->up, &uw, &uh);
        printf("swell: render scale %.2f: the frame drawn at %dx%d, stretched over %dx%d\n",
               o->scale, uw, uh, w, h);
    }
    printf("swell: GL %s | %s | %s\n", gl_string(GL_VENDOR), gl_string(GL_RENDERER),
           gl_string(GL_VERSION));
    printf("swell: tier %s (available %s%s)\n", glapp_tier_name(app->st.tier),
           glapp_tier_name(app->st.tier_available), o->tier != SWELL_TIER_BEST ? ", forced" : "");
    swell_sea_info info;
    swell_sea_get_info(app->sea, &info);
    printf("swell: tables %s: %d patterns, %d frames over %.1f s, Hs %.2f m, wind %.1f m/s\n",
           o->tables_dir ? o->tables_dir : "(baked in memory)", info.patterns, info.frames,
           (double)info.loop_period_s, (double)info.significant_height_m,
           (double)info.wind_speed_mps);
    char desc[4096];
    swell_ocean_describe(app->ocean, desc, sizeof desc);
    printf("%s%s", desc, desc[0] && desc[strlen(desc) - 1] != '\n' ? "\n" : "");
    swell_ocean_stats st;
    swell_ocean_get_stats(app->ocean, &st);
    printf("swell: GPU memory %.2f MiB of %.2f MiB budget (renderer %.2f MiB), %d vertices, "
           "%d triangles, %.1f KiB streamed per frame\n", st.gpu_bytes_charged / 1048576.0,
           st.budget_bytes / 1048576.0, st.gpu_bytes / 1048576.0, st.vertices, st.triangles,
           st.cpu_bytes_per_frame / 1024.0);
    /* The display's frame (tables/budget.h: not the sea's, not charged): one colour buffer
     * offscreen, at least two for KMS page flips, and the depth buffer. */
    GLint depth_bits = 0;
    glGetIntegerv(GL_DEPTH_BITS, &depth_bits);
    int buffers = strcmp(app->ph->be->name, "kms") == 0 ? 2 : 1;
    double fb = (double)w * (double)h * (4.0 * buffers + (double)((depth_bits + 7) / 8));
    printf("swell: frame buffers %.2f MiB (%d colour at %dx%d and %d-bit depth: the display's, "
           "not in the sea's budget)\n", fb / 1048576.0, buffers, w, h, (int)depth_bits);
    fflush(stdout);
}

/* --mask: the PNG's grey levels (red), north up, as the ocean's wave mask over --mask-area.
 * A driver that runs no program with the mask draws the open sea, saying so. */
static int load_mask(struct app *app, struct swell_err *err)
{
    const struct options *o = app->o;
    uint8_t *rgba = NULL;
    int w = 0, h = 0;
    int rc = image_read_png(o->mask_path, &rgba, &w, &h, err);
    if (rc) {
        swell_err_context(err, "--mask");
        return rc;
    }
    if (w > SWELL_MASK_MAX_TEXELS || h > SWELL_MASK_MAX_TEXELS) {
        free(rgba);
        return swell_fail(err, SWELL_E_ARG, "--mask: %s is %d x %d pixels; a wave mask has at "
                          "most %d x %d (a coarse one: tens of metres a pixel): scale it down",
                          o->mask_path, w, h, SWELL_MASK_MAX_TEXELS, SWELL_MASK_MAX_TEXELS);
    }
    uint8_t *amp = malloc((size_t)w * (size_t)h);
    if (!amp) {
        free(rgba);
        return swell_fail(err, SWELL_E_NOMEM, "--mask: no memory");
    }
    for (int j = 0; j < h; j++)   /* the mask's row 0 is its south edge, the image's bottom */
        for (int i = 0; i < w; i++)
            amp[(size_t)j * (size_t)w + (size_t)i] =
                rgba[4 * ((size_t)(h - 1 - j) * (size_t)w + (size_t)i)];
    free(rgba);
    swell_mask m = { .amplitude = amp, .width = w, .height = h,
                     .origin_m = { o->mask_area[0], o->mask_area[1] },
                     .size_m = { o->mask_area[2], o->mask_area[3] } };
    if (!app->st.objects) {
        fprintf(stderr, "swell: --mask: this GPU's driver runs no program with the wave mask; "
                "the open sea is drawn\n");
    } else if ((rc = swell_ocean_set_mask(app->ocean, &m, err))) {
        swell_err_context(err, "--mask");
    }
    free(amp);
    return rc;
}

/* The ocean, the render scale and the boat in the platform's context. */
static int open_ocean(struct app *app, struct swell_err *err)
{
    const struct options *o = app->o;
    swell_ocean_desc od = {
        .quality = o->quality, .geometry = o->geometry, .tier = o->tier, .detile = o->detile,
        .sun_elev_deg = o->sun_elev_deg, .sun_azim_deg = o->sun_azim_deg,
        .pixel_lod = o->pixel_lod, .debug_programs = o->debug_variants,
        .reflections = o->boat, .wakes = o->boat, .shadows = o->boat, .refractions = o->boat,
        .wave_mask = o->mask_path != NULL, .note = note_fallback,
    };
    int rc = swell_ocean_create(app->sea, &od, &app->ocean, err);
    if (rc)
        return rc;
    swell_ocean_get_stats(app->ocean, &app->st);
    if (o->mask_path && (rc = load_mask(app, err)))
        return rc;
    if (o->scale > 0 && o->scale < 1) {
        /* the output's framebuffer is bound here (the platform's) */
        GLint depth_bits = 0;
        glGetIntegerv(GL_DEPTH_BITS, &depth_bits);
        if ((rc = swell_upscale_create(app->ocean, app->out_w, app->out_h, o->scale, depth_bits,
                                       &app->up, err)))
            return rc;
    }
    if (o->boat) {
        /* 30 m ahead of the first frame's camera */
        struct camera c0 = o->camera;
        if (o->path > CAMERA_PATH_NONE)
            camera_path_at(o->path, o->time0_s, &c0);
        double hd = c0.heading_deg * M_PI / 180.0;
        struct boat_desc bd = {
            .x0 = c0.pos[0] + 30.0 * cos(hd), .y0 = c0.pos[1] + 30.0 * sin(hd),
            .t0_s = o->time0_s, .heading_deg = o->boat_heading_deg,
            .speed_mps = o->boat_speed_mps,
        };
        if ((rc = boat_create(&bd, app->st.tier, &app->boat, err)))
            return rc;
        app->boat_shown = 1;
    }
    return SWELL_OK;
}

int main(int argc, char **argv)
{
    struct options o;
    memset(&o, 0, sizeof o);
    o.frames = -1;
    o.warmup = -1;
    camera_defaults(&o.camera);
    int rc = options_parse(argc, argv, &o);
    if (rc)
        return rc;

    struct swell_err err = { 0 };
    struct platform_handle ph = { 0 };
    struct app app = {
        .o = &o, .ph = &ph, .sun_azim_deg = o.sun_azim_deg,
        /* 0 means the ocean's default elevation (swell.h) */
        .sun_elev_deg = o.sun_elev_deg > 0.0f ? o.sun_elev_deg : 30.0f,
    };
    int status = 1;

    if (load_sea(&o, &app.sea, &err))
        goto fail;
    /* A GLES 3 context unless a lower tier is forced (then GLES 2, as such a device has). */
    o.platform.gles_major = (o.tier == SWELL_TIER_BEST || o.tier == SWELL_TIER_GLES3) ? 3 : 2;
    if (platform_open(&o.platform, &ph, &err))
        goto fail_sea;
    ph.be->size(ph.p, &app.out_w, &app.out_h);
    if (open_ocean(&app, &err))
        goto fail_ocean;
    print_start(&app);
    if (o.bench ? run_bench(&app, &err) : run_frames(&app, ph.be == &platform_kms_backend, &err))
        goto fail_ocean;
    status = 0;

fail_ocean:
    boat_destroy(app.boat);
    swell_upscale_destroy(app.up);
    swell_ocean_destroy(app.ocean);
    platform_close(&ph);
fail_sea:
    swell_sea_destroy(app.sea);
fail:
    if (status)
        fprintf(stderr, "swell: %s (%s)\n", err.msg, swell_err_name(err.code));
    return status;
}
