/* options.h - swell's command line (options.c): what it asks for, parsed and checked against
 * each other before anything is opened; --help's text. */
#ifndef SWELL_APP_OPTIONS_H
#define SWELL_APP_OPTIONS_H

#include <stdint.h>
#include "core/camera.h"
#include "core/seastate.h"
#include "platform/platform.h"

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
    int boat;                   /* --boat: the demo boat (app/boat.h) */
    float boat_speed_mps, boat_heading_deg;
};

/* --out's text: -1 when not a file name or a pattern with one %d, else its %d count (0, 1). */
int options_out_conversions(const char *s);

/* Fill o from argv: 0, 2 for a usage error (printed), or exit(0) after --help or --version. */
int options_parse(int argc, char **argv, struct options *o);

#endif
