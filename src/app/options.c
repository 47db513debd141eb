/* options.c - swell's command line (options.h): each option parsed by core/parse.h, the sea's
 * checked by swell_sea_check (swell.h), the combinations that cannot work refused with what to
 * do instead. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "app/glapp.h"
#include "app/options.h"
#include "core/args.h"
#include "core/parse.h"
#include "platform/input.h"
#include "swell.h"

/* The names of swell.h's enums on the command line, indexed by value. */
static const char *const quality_names[] = { "high", "low" };
static const char *const geometry_names[] = { "grid", "patches" };
static const char *const detile_names[] = { "auto", "on", "off" };
#define COUNT(t) (int)(sizeof t / sizeof t[0])

const char *options_quality_name(int q)
{
    return name_of(quality_names, COUNT(quality_names), q);
}

const char *options_geometry_name(int g)
{
    return name_of(geometry_names, COUNT(geometry_names), g);
}

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
"  --boat SPEED,HDG  a demo boat 30 m ahead of the camera, sailing at SPEED m/s\n"
"                    (0..20) on course HDG deg (CCW from east), floating on the sea by\n"
"                    its CPU query, reflected in it; B on KMS shows or hides it  [none]\n"
"  --mask FILE.png   the waves' amplitude over an area by the image's grey levels (a\n"
"                    colour image's red): white the open sea, black still water (an\n"
"                    island's lee); at most 254 x 254 pixels, north up           [none]\n"
"  --mask-area X0,Y0,W,H  where the mask lies: its south-west corner and size, m\n"
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
            SWELL_WIND_SPEED_MIN_MPS, SWELL_WIND_SPEED_MAX_MPS);
    size_t n = swell_sea_usage(SWELL_USAGE_DATA, NULL, 0);
    char *text = malloc(n + 1);
    if (text) {
        swell_sea_usage(SWELL_USAGE_DATA, text, n + 1);
        fputs(text, f);
        free(text);
    }
}

/* A --preset or --wind for the sea baked in memory: kept as swell_sea_desc options and checked
 * with those before it as the bake will apply them (a budget it cannot fit is the bake's to
 * say, at run time). */
static int sea_option(struct options *o, const char *name, const char *value,
                      struct swell_err *err)
{
    if (o->sea_count >= OPTIONS_SEA_MAX)
        return swell_fail(err, SWELL_E_ARG, "%s: more than %d --preset and --wind options",
                          name, OPTIONS_SEA_MAX);
    o->baking = 1;
    o->sea[2 * o->sea_count] = name;
    o->sea[2 * o->sea_count + 1] = value;
    o->sea_count++;
    o->sea[2 * o->sea_count] = NULL;
    swell_sea_desc d = { .options = o->sea };
    int rc = swell_sea_check(&d, err);
    return rc == SWELL_E_BUDGET ? SWELL_OK : rc;
}

/* The --out text: plain, or exactly one %d conversion with optional 0 flag and width; "%%" is a
 * literal percent. Anything else could read arguments that are not there. Returns the number of
 * conversions, or -1 if the pattern is not allowed. */
#define OUT_MAX_WIDTH 32       /* digits a frame number may be padded to */

int options_out_conversions(const char *s)
{
    int n = 0;
    for (const char *p = s; *p; p++) {
        if (*p != '%')
            continue;
        p++;
        if (*p == '%')
            continue;
        long width = 0;
        while (*p >= '0' && *p <= '9') {
            width = 10 * width + (*p - '0');
            if (width > OUT_MAX_WIDTH)
                return -1;      /* printf's width overflowed into one file for every frame */
            p++;
        }
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

int options_parse(int argc, char **argv, struct options *o)
{
    static const char *const flags[] = { "--verbose", "--bench", NULL };
    static const char *const valued[] = {
        "--platform", "--size", "--frames", "--fps", "--time", "--duration", "--out", "--tables",
        "--preset", "--wind", "--budget", "--sun", "--camera", "--heading", "--pitch", "--path",
        "--roll", "--quality", "--geometry", "--tier", "--lod", "--device", "--connector", "--mode",
        "--kms-api", "--warmup", "--results", "--scene", "--debug", "--detile", "--scale", "--boat",
        "--mask", "--mask-area", NULL,
    };
    struct args args = { "swell", argc, argv, 1, flags, valued, NULL, usage,
                         "swell " SWELL_VERSION_STRING };
    struct swell_err err = { 0 };
    const char *a, *v;
    int r = 0, k;
    while (!r && (k = args_next(&args, &a, &v)) != ARGS_END) {
        if (k == ARGS_ERROR)
            return 2;
        if (k == ARGS_DONE)
            exit(0);
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
            if (!v[0] || options_out_conversions(v) < 0)
                r = swell_fail(&err, SWELL_E_ARG, "--out: '%s' is not a file name or a pattern "
                               "with one %%d conversion, padded to at most %d digits (e.g. "
                               "out/frame%%04d.png)", v, OUT_MAX_WIDTH);
            else if (len < 4 || strcasecmp(v + len - 4, ".png") != 0)
                r = swell_fail(&err, SWELL_E_ARG, "--out: '%s' does not end in .png (frames are "
                               "written as PNG only)", v);
        } else if (!strcmp(a, "--tables")) {
            o->tables_dir = v;
            if (!v[0])
                r = swell_fail(&err, SWELL_E_ARG, "--tables: empty directory name");
        } else if (!strcmp(a, "--preset") || !strcmp(a, "--wind")) {
            r = sea_option(o, a, v, &err);
        } else if (!strcmp(a, "--budget")) {
            r = parse_budget(a, v, &o->budget, &err);
        } else if (!strcmp(a, "--sun")) {
            double s[2];
            r = parse_doubles(a, v, 2, -360, 360, s, &err);
            if (!r && (s[0] <= 0 || s[0] > 90))
                r = swell_fail(&err, SWELL_E_ARG, "--sun: elevation %g in '%s' is out of range "
                               "(degrees, above 0 up to 90)", s[0], v);
            o->sun_elev_deg = (float)s[0];
            o->sun_azim_deg = (float)s[1];
        } else if (!strcmp(a, "--boat")) {
            double s[2];
            r = parse_doubles(a, v, 2, -360, 360, s, &err);
            if (!r && (s[0] < 0 || s[0] > 20))
                r = swell_fail(&err, SWELL_E_ARG, "--boat: speed %g m/s in '%s' is out of "
                               "range (0 to 20)", s[0], v);
            o->boat = 1;
            o->boat_speed_mps = (float)s[0];
            o->boat_heading_deg = (float)s[1];
        } else if (!strcmp(a, "--mask")) {
            o->mask_path = v;
            if (!v[0])
                r = swell_fail(&err, SWELL_E_ARG, "--mask: empty file name (a grey PNG)");
        } else if (!strcmp(a, "--mask-area")) {
            r = parse_doubles(a, v, 4, -1e9, 1e9, o->mask_area, &err);
            if (!r && (!(o->mask_area[2] > 0.0) || o->mask_area[2] > 1e6 ||
                       !(o->mask_area[3] > 0.0) || o->mask_area[3] > 1e6))
                r = swell_fail(&err, SWELL_E_ARG, "--mask-area: width %g and height %g m in "
                               "'%s' must be above 0 and at most 1e6 m", o->mask_area[2],
                               o->mask_area[3], v);
            o->mask_area_given = 1;
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
            o->quality = parse_name(quality_names, 0, COUNT(quality_names), v);
            if (o->quality < 0)
                r = swell_fail(&err, SWELL_E_ARG, "--quality: '%s' is not low or high", v);
        } else if (!strcmp(a, "--geometry")) {
            o->geometry = parse_name(geometry_names, 0, COUNT(geometry_names), v);
            if (o->geometry < 0)
                r = swell_fail(&err, SWELL_E_ARG, "--geometry: '%s' is not grid or patches", v);
        } else if (!strcmp(a, "--tier")) {
            o->tier = -1;
            for (int t = SWELL_TIER_GLES2_MIN; t <= SWELL_TIER_GLES3; t++)
                if (!strcmp(v, glapp_tier_name(t)))
                    o->tier = t;
            if (o->tier < 0)
                r = swell_fail(&err, SWELL_E_ARG, "--tier: '%s' is not gles2-min, gles2-ext or "
                               "gles3", v);
        } else if (!strcmp(a, "--lod")) {
            if (!strcmp(v, "auto") || !strcmp(v, "pixel"))
                o->pixel_lod = !strcmp(v, "pixel");
            else
                r = swell_fail(&err, SWELL_E_ARG, "--lod: '%s' is not auto or pixel", v);
        } else if (!strcmp(a, "--detile")) {
            o->detile = parse_name(detile_names, 0, COUNT(detile_names), v);
            if (o->detile < 0)
                r = swell_fail(&err, SWELL_E_ARG, "--detile: '%s' is not auto, on or off", v);
        } else if (!strcmp(a, "--scale")) {
            r = parse_double(a, v, SWELL_UPSCALE_MIN, SWELL_UPSCALE_MAX, "x the output's size",
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
    if (!o->mask_path != !o->mask_area_given) {
        fprintf(stderr, "swell: --mask FILE.png and --mask-area X0,Y0,W,H go together: the "
                "image's grey levels and where on the sea it lies, m\n");
        return 2;
    }
    if (o->debug_variants && o->scale > 0 && o->scale < 1) {
        fprintf(stderr, "swell: --debug variants counts the pixels each program draws, which "
                "the stretch of --scale blends: give --scale 1\n");
        return 2;
    }
    if (o->out && o->frames != 1 && options_out_conversions(o->out) == 0 &&
        (o->frames > 1 || o->duration_s > 0)) {
        fprintf(stderr, "swell: --out: '%s' has no %%d pattern but more than one frame is "
                "rendered (e.g. out/frame%%04d.png)\n", o->out);
        return 2;
    }
    return 0;
}
