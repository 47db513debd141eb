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
#include <strings.h>
#include <time.h>

#include "bake/bake.h"
#include "app/bench.h"
#include "core/args.h"
#include "core/datadir.h"
#include "swell.h"
#include "core/camera.h"
#include "gl/gpu.h"
#include "core/image.h"
#include "platform/input.h"
#include "core/parse.h"
#include "platform/platform.h"
#include "core/preset.h"
#include "render/renderer.h"
#include "tables/tables_io.h"
#include "render/upscale.h"

#define DEFAULT_FPS 30.0
#define MAX_PATH_LEN 4096

struct options {
    struct platform_desc platform;
    int frames;                 /* -1 = by platform: 1 offscreen, unlimited on KMS */
    double fps;                 /* animation time step 1/fps; 0 = default (wall clock on KMS) */
    double time0_s;
    double duration_s;          /* 0 = none */
    const char *out;            /* PNG path or printf pattern with one %d */
    const char *tables_dir;
    int baking;                 /* a --preset or --wind was given */
    struct seastate state;
    uint64_t budget;            /* 0 = the tables' own */
    float sun_elev_deg, sun_azim_deg;
    int camera_given, path;
    struct camera camera;
    int quality, geometry, tier;
    int pixel_lod;              /* --lod pixel */
    int debug_uncovered;        /* --debug uncovered */
    int debug_variants;         /* --debug variants */
    int detile;                 /* --detile: enum detile_mode */
    double scale;               /* --scale: render scale (upscale.h); 0 = 1 */
    int verbose;
    int bench;                  /* --bench: time frames against the baseline quad */
    int warmup;                 /* --warmup: untimed bench frames; -1 = default */
    const char *results;        /* --results FILE.json */
    const char *scene;          /* --scene: label in the results */
};

static void usage(FILE *f)
{
    fprintf(f,
"usage: swell [options]       render the ocean (KMS display, or PNG frames offscreen)\n"
"\n"
"Output:\n"
"  --platform P      surfaceless | kms | auto (KMS when a display is connected)      [auto]\n"
"  --size WxH        offscreen frame size, pixels                               [1280x720]\n"
"  --frames N        frames to render; 0 = until quit or --duration\n"
"                                            [1 offscreen, 0 on KMS, or duration x fps]\n"
"  --fps F           animation step 1/F s per frame, frames/s            [30; KMS: clock]\n"
"  --time S          animation time of the first frame, s                            [0]\n"
"  --duration S      stop after S s of animation time                             [none]\n"
"  --out FILE.png    write frames as PNG; a sequence needs a pattern such as\n"
"                    out/frame%%04d.png (one %%d conversion)                        [none]\n"
"Sea (tables):\n"
"  --tables DIR      load baked tables from DIR (see swell-bake)\n"
"  --preset NAME     bake in memory from NAME.preset in tables/ (Data, below) or a .preset\n"
"                    path; repeats\n"
"  --wind U          bake in memory with wind speed U10, m/s (%g..%g)               [10]\n"
"  --budget B        GPU memory budget: tiny (4 MiB), default (16 MiB) or bytes (8M)\n"
"                                                                [the tables' budget]\n"
"                    (without --tables/--preset/--wind the default sea state is baked)\n"
"View:\n"
"  --sun ELEV,AZIM   sun elevation above the horizon (0..90] and azimuth CCW from east,\n"
"                    degrees                                                      [30,0]\n"
"  --camera X,Y,Z    camera position, m (x east, y north, z altitude 0.1..500000) [0,0,10]\n"
"  --heading DEG     view direction CCW from east, degrees (-360..360)               [0]\n"
"  --pitch DEG       view pitch, degrees, negative looks down (-89..89)            [-10]\n"
"  --roll DEG        bank about the view axis, degrees, positive raises the right\n"
"                    side (-180..180)                                              [0]\n"
"  --path P          scripted camera: surface | 1km | 10km | orbit (400 km; overrides\n"
"                    --camera)                                                   [none]\n"
"Rendering:\n"
"  --quality Q       low | high                                                   [high]\n"
"  --geometry G      grid (projected grid) | patches (near/far patches)           [grid]\n"
"  --tier T          force a lower device tier: gles2-min | gles2-ext | gles3      [best]\n"
"  --lod L           texture level: auto (one whole level per run of rows on software\n"
"                    rasterisers, per pixel on GPUs) | pixel (per pixel, as GPUs) [auto]\n"
"  --detile D        on: each wave pattern read at three random offsets blended, so no\n"
"                    pattern repeats on its tile (2-3.5x the frame on llvmpipe) | off:\n"
"                    read once, the tiles repeat | auto: on in high quality, off in\n"
"                    low                                                         [auto]\n"
"  --scale S         render scale: the frame drawn at S x the output's size and\n"
"                    stretched over it, bilinear (0.25..1; S^2 of the pixels shaded:\n"
"                    for GPUs too slow to shade every pixel, docs/devices.md)         [1]\n"
"KMS (fullscreen until Esc, q or Ctrl-C; the frame rate printed every 2 s):\n"
"  --device PATH     DRM device such as /dev/dri/card0       [first with a display]\n"
"  --connector NAME  connector such as HDMI-A-1 or Virtual-1    [first connected]\n"
"  --mode WxH[@HZ]   display mode, exact else nearest                   [preferred]\n"
"  --kms-api A       atomic | legacy | auto (atomic when available)            [auto]\n"
"Benchmark (see docs/bench.md, make bench):\n"
"  --bench           time whole frames (each ends with glFinish) against a one-textured-\n"
"                    fullscreen-quad baseline drawn in the same run; --frames N timed\n"
"                    frames (>= 100 for published numbers), --time/--fps/--path as above [100]\n"
"  --warmup N        untimed frames before the timed ones                          [10]\n"
"  --results FILE    write the measurements as JSON (atomically)                 [none]\n"
"  --scene NAME      scene name recorded in the results             [tables or preset]\n"
"Other:\n"
"  --debug uncovered clear to magenta (255, 0, 255) before the sky and the sea are drawn,\n"
"                    so a pixel neither covers shows; the camera is kept 0.3 m above the\n"
"                    sea surface under it in every mode (no view from under the water)\n"
"  --debug variants  draw each run of sea rows in a flat colour naming its shader program,\n"
"                    no sky, and print each frame's share of the screen per program\n"
"                    (tools/devices.py's cost model)\n"
"  --verbose         print the chosen device, mode, EGL config and per-frame stats\n"
"  --help            this text\n"
"  --version         print the version\n"
"\n"
"Exit status: 0 success, 1 runtime failure, 2 usage error.\n\n",
            seastate_option("--wind")->lo, seastate_option("--wind")->hi);
    data_dir_usage(f);
}

/* The --out text: plain, or exactly one %d conversion with optional 0 flag and width; "%%" is a
 * literal percent. Anything else could read arguments that are not there. Returns the number of
 * conversions, or -1 if the pattern is not allowed. */
static int out_conversions(const char *s)
{
    int n = 0;
    for (const char *p = s; *p; p++) {
        if (*p != '%')
            continue;
        p++;
        if (*p == '%')
            continue;
        while (*p >= '0' && *p <= '9')
            p++;
        if (*p != 'd')
            return -1;
        n++;
    }
    return n > 1 ? -1 : n;
}

static int parse_mode(const char *opt, const char *v, struct platform_desc *d,
                      struct swell_err *err)
{
    char buf[64];
    if (strlen(v) >= sizeof buf)
        return swell_fail(err, SWELL_E_ARG, "%s: '%s' is not WxH[@HZ] (e.g. 1920x1080@60)",
                          opt, v);
    strcpy(buf, v);
    char *at = strchr(buf, '@');
    if (at) {
        *at = '\0';
        if (parse_int(opt, at + 1, 1, 1000, &d->mode_hz, err))
            return swell_fail(err, SWELL_E_ARG, "%s: '%s' is not WxH[@HZ] with HZ 1 to 1000 "
                              "(e.g. 1920x1080@60)", opt, v);
    }
    return parse_wxh(opt, buf, 16, 16384, &d->mode_w, &d->mode_h, err);
}

static int parse_args(int argc, char **argv, struct options *o)
{
    static const char *const flags[] = { "--verbose", "--bench", NULL };
    static const char *const valued[] = {
        "--platform", "--size", "--frames", "--fps", "--time", "--duration", "--out", "--tables",
        "--preset", "--wind", "--budget", "--sun", "--camera", "--heading", "--pitch", "--path",
        "--roll", "--quality", "--geometry", "--tier", "--lod", "--device", "--connector", "--mode",
        "--kms-api", "--warmup", "--results", "--scene", "--debug", "--detile", "--scale", NULL,
    };
    struct args args = { "swell", argc, argv, 1, flags, valued, 0 };
    struct swell_err err = { 0 };
    const char *a, *v;
    int r = 0, k;
    while (!r && (k = args_next(&args, &a, &v)) != ARGS_END) {
        if (k == ARGS_ERROR)
            return 2;
        if (k == ARGS_HELP) {
            usage(stdout);
            exit(0);
        }
        if (k == ARGS_VERSION) {
            printf("swell " SWELL_VERSION_STRING "\n");
            exit(0);
        }
        if (!strcmp(a, "--verbose")) {
            o->verbose = o->platform.verbose = 1;
        } else if (!strcmp(a, "--bench")) {
            o->bench = 1;
        } else if (!strcmp(a, "--platform")) {
            if (!strcmp(v, "auto")) o->platform.kind = PLATFORM_AUTO;
            else if (!strcmp(v, "surfaceless")) o->platform.kind = PLATFORM_SURFACELESS;
            else if (!strcmp(v, "kms")) o->platform.kind = PLATFORM_KMS;
            else r = swell_fail(&err, SWELL_E_ARG, "--platform: '%s' is not surfaceless, kms or auto", v);
        } else if (!strcmp(a, "--size")) {
            r = parse_wxh(a, v, 16, 16384, &o->platform.width, &o->platform.height, &err);
        } else if (!strcmp(a, "--frames")) {
            r = parse_int(a, v, 0, 100000000L, &o->frames, &err);
        } else if (!strcmp(a, "--fps")) {
            r = parse_double(a, v, 0.1, 1000, "frames/s", &o->fps, &err);
        } else if (!strcmp(a, "--time")) {
            r = parse_double(a, v, -1e7, 1e7, "s", &o->time0_s, &err);
        } else if (!strcmp(a, "--duration")) {
            r = parse_double(a, v, 0.001, 1e7, "s", &o->duration_s, &err);
        } else if (!strcmp(a, "--out")) {
            o->out = v;
            size_t len = strlen(v);
            if (!v[0] || out_conversions(v) < 0)
                r = swell_fail(&err, SWELL_E_ARG, "--out: '%s' is not a file name or a pattern "
                               "with one %%d conversion (e.g. out/frame%%04d.png)", v);
            else if (len < 4 || strcasecmp(v + len - 4, ".png") != 0)
                r = swell_fail(&err, SWELL_E_ARG, "--out: '%s' does not end in .png (frames are "
                               "written as PNG only)", v);
        } else if (!strcmp(a, "--tables")) {
            o->tables_dir = v;
            if (!v[0])
                r = swell_fail(&err, SWELL_E_ARG, "--tables: empty directory name");
        } else if (!strcmp(a, "--preset")) {
            o->baking = 1;
            r = preset_load(v, &o->state, &err);
        } else if (!strcmp(a, "--wind")) {
            o->baking = 1;
            r = seastate_set_option(&o->state, seastate_option(a), v, &err);
        } else if (!strcmp(a, "--budget")) {
            struct seastate b = { 0 };
            r = seastate_set_option(&b, seastate_option(a), v, &err);
            o->budget = b.budget_bytes;
        } else if (!strcmp(a, "--sun")) {
            double s[2];
            r = parse_doubles(a, v, 2, -360, 360, s, &err);
            if (!r && (s[0] <= 0 || s[0] > 90))
                r = swell_fail(&err, SWELL_E_ARG, "--sun: elevation %g in '%s' is out of range "
                               "(degrees, above 0 up to 90)", s[0], v);
            o->sun_elev_deg = (float)s[0];
            o->sun_azim_deg = (float)s[1];
        } else if (!strcmp(a, "--camera")) {
            r = parse_doubles(a, v, 3, -1e7, 1e7, o->camera.pos, &err);
            if (!r && (o->camera.pos[2] < 0.1 || o->camera.pos[2] > INPUT_ALT_MAX_M))
                r = swell_fail(&err, SWELL_E_ARG, "--camera: altitude %g m in '%s' is out of "
                               "range (0.1 to %.0f m)", o->camera.pos[2], v, INPUT_ALT_MAX_M);
            o->camera_given = 1;
        } else if (!strcmp(a, "--heading")) {
            r = parse_float(a, v, -360, 360, "deg", &o->camera.heading_deg, &err);
        } else if (!strcmp(a, "--pitch")) {
            r = parse_float(a, v, -89, 89, "deg", &o->camera.pitch_deg, &err);
        } else if (!strcmp(a, "--roll")) {
            r = parse_float(a, v, -180, 180, "deg", &o->camera.roll_deg, &err);
        } else if (!strcmp(a, "--path")) {
            o->path = camera_path_from_name(v);
            if (o->path <= CAMERA_PATH_NONE)
                r = swell_fail(&err, SWELL_E_ARG, "--path: '%s' is not surface, 1km, 10km or orbit",
                               v);
        } else if (!strcmp(a, "--quality")) {
            o->quality = render_quality_from_name(v);
            if (o->quality < 0)
                r = swell_fail(&err, SWELL_E_ARG, "--quality: '%s' is not low or high", v);
        } else if (!strcmp(a, "--geometry")) {
            o->geometry = geometry_kind_from_name(v);
            if (o->geometry < 0)
                r = swell_fail(&err, SWELL_E_ARG, "--geometry: '%s' is not grid or patches", v);
        } else if (!strcmp(a, "--tier")) {
            o->tier = gpu_tier_from_name(v);
            if (o->tier < 0)
                r = swell_fail(&err, SWELL_E_ARG, "--tier: '%s' is not gles2-min, gles2-ext or "
                               "gles3", v);
        } else if (!strcmp(a, "--lod")) {
            if (!strcmp(v, "auto") || !strcmp(v, "pixel"))
                o->pixel_lod = !strcmp(v, "pixel");
            else
                r = swell_fail(&err, SWELL_E_ARG, "--lod: '%s' is not auto or pixel", v);
        } else if (!strcmp(a, "--detile")) {
            o->detile = detile_mode_from_name(v);
            if (o->detile < 0)
                r = swell_fail(&err, SWELL_E_ARG, "--detile: '%s' is not auto, on or off", v);
        } else if (!strcmp(a, "--scale")) {
            r = parse_double(a, v, UPSCALE_MIN, UPSCALE_MAX, "x the output's size",
                             &o->scale, &err);
        } else if (!strcmp(a, "--device")) {
            o->platform.device = v;
            if (!v[0])
                r = swell_fail(&err, SWELL_E_ARG, "--device: empty path (e.g. /dev/dri/card0)");
        } else if (!strcmp(a, "--connector")) {
            o->platform.connector = v;
            if (!v[0])
                r = swell_fail(&err, SWELL_E_ARG, "--connector: empty name (e.g. HDMI-A-1)");
        } else if (!strcmp(a, "--mode")) {
            r = parse_mode(a, v, &o->platform, &err);
        } else if (!strcmp(a, "--debug")) {
            if (!strcmp(v, "uncovered"))
                o->debug_uncovered = 1;
            else if (!strcmp(v, "variants"))
                o->debug_variants = 1;
            else
                r = swell_fail(&err, SWELL_E_ARG, "--debug: '%s' is neither uncovered nor "
                               "variants (the debug views)", v);
        } else if (!strcmp(a, "--warmup")) {
            r = parse_int(a, v, 0, 100000, &o->warmup, &err);
        } else if (!strcmp(a, "--results")) {
            o->results = v;
            if (!v[0])
                r = swell_fail(&err, SWELL_E_ARG, "--results: empty file name");
        } else if (!strcmp(a, "--scene")) {
            o->scene = v;
        } else if (!strcmp(a, "--kms-api")) {
            if (!strcmp(v, "auto")) o->platform.kms_api = KMS_API_AUTO;
            else if (!strcmp(v, "atomic")) o->platform.kms_api = KMS_API_ATOMIC;
            else if (!strcmp(v, "legacy")) o->platform.kms_api = KMS_API_LEGACY;
            else r = swell_fail(&err, SWELL_E_ARG, "--kms-api: '%s' is not atomic, legacy or auto", v);
        } else {
            fprintf(stderr, "swell: unknown option '%s' (see --help)\n", a);
            return 2;
        }
    }
    if (r) {
        fprintf(stderr, "swell: %s\n", err.msg);
        return 2;
    }
    if (o->tables_dir && o->baking) {
        fprintf(stderr, "swell: --tables loads baked tables; --preset/--wind bake new ones: "
                "give one or the other\n");
        return 2;
    }
    if (!o->bench && (o->results || o->warmup >= 0 || o->scene)) {
        fprintf(stderr, "swell: --results, --warmup and --scene go with --bench\n");
        return 2;
    }
    if (o->bench && (o->out || o->duration_s > 0 || o->frames == 0)) {
        fprintf(stderr, "swell: --bench times a fixed number of frames (--frames N, N >= 1) "
                "and writes no PNG: drop --out/--duration\n");
        return 2;
    }
    if (o->debug_variants && o->scale > 0 && o->scale < 1) {
        fprintf(stderr, "swell: --debug variants counts the pixels each program draws, which "
                "the stretch of --scale blends: give --scale 1\n");
        return 2;
    }
    if (o->out && o->frames != 1 && out_conversions(o->out) == 0 &&
        (o->frames > 1 || o->duration_s > 0)) {
        fprintf(stderr, "swell: --out: '%s' has no %%d pattern but more than one frame is "
                "rendered (e.g. out/frame%%04d.png)\n", o->out);
        return 2;
    }
    return 0;
}

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
        int rc = tables_load_dir(o->tables_dir, t, err);
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
static int run_frames(const struct options *o, struct platform_handle *ph, struct renderer *r,
                      struct upscale *up, int is_kms, struct swell_err *err)
{
    int w = 0, h = 0;
    ph->be->size(ph->p, &w, &h);
    int frames = o->frames;
    if (frames < 0) {
        double fps = o->fps > 0 ? o->fps : DEFAULT_FPS;
        frames = o->duration_s > 0 ? (int)ceil(o->duration_s * fps) : (is_kms ? 0 : 1);
    }
    if (frames == 0 && !is_kms && o->duration_s <= 0)
        return swell_fail(err, SWELL_E_ARG, "--frames 0 renders until quit, which never comes "
                          "offscreen; give --frames N or --duration S");
    if (o->out && out_conversions(o->out) == 0 && frames != 1)
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
        struct camera cam = live;
        if (o->path > CAMERA_PATH_NONE)
            camera_path_at(o->path, t, &cam);
        rc = ph->be->begin_frame(ph->p, err);
        if (!rc && up)
            upscale_begin(up);
        if (!rc)
            rc = renderer_frame(r, &cam, t, up ? up->w : w, up ? up->h : h, err);
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

/* --bench: bench.c runs the frames; this prints the one-line summary and writes --results. */
static int run_bench(const struct options *o, struct platform_handle *ph, struct gpu *g,
                     struct renderer *r, struct upscale *up, struct swell_err *err)
{
    struct bench_desc bd = {
        .ph = ph, .renderer = r, .gpu = g, .upscale = up, .camera = o->camera, .path = o->path,
        .time0_s = o->time0_s, .step_s = 1.0 / (o->fps > 0 ? o->fps : DEFAULT_FPS),
        .warmup = o->warmup < 0 ? 0 : o->warmup == 0 ? -1 : o->warmup,
        .frames = o->frames > 0 ? o->frames : 0,
        .scene = o->scene ? o->scene : o->tables_dir ? o->tables_dir : "baked in memory",
        .quality = render_quality_name(o->quality), .geometry = geometry_kind_name(o->geometry),
        .detile = renderer_detile(r) ? "on" : "off",
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
    int rc = parse_args(argc, argv, &o);
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
        .detile = o.detile,
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
    print_start(&o, &ph, &gpu, &tables, r, up);
    if (o.bench ? run_bench(&o, &ph, &gpu, r, up, &err)
                : run_frames(&o, &ph, r, up, ph.be == &platform_kms_backend, &err))
        goto fail_upscale;
    status = 0;

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
