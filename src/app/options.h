/* options.h - swell's command line (options.c): what it asks for, parsed and checked against
 * each other before anything is opened; --help's text. */
#ifndef SWELL_APP_OPTIONS_H
#define SWELL_APP_OPTIONS_H

#include <stdint.h>
#include "core/camera.h"
#include "platform/platform.h"
#include "swell.h"

#define DEFAULT_FPS 30.0
#define MAX_PATH_LEN 4096
#define OPTIONS_SEA_MAX 64      /* --preset and --wind options at most */

struct options {
    struct platform_desc platform;
    int frames;                 /* -1 = by platform: 1 offscreen, unlimited on KMS */
    double fps;                 /* animation time step 1/fps; 0 = default (wall clock on KMS) */
    double time0_s;
    double duration_s;          /* 0 = none */
    const char *out;            /* PNG path or printf pattern with one %d */
    const char *tables_dir;
    int baking;                 /* a --preset or --wind was given */
    const char *sea[2 * OPTIONS_SEA_MAX + 1];  /* those, as name and value pairs ending in NULL
                                 * (swell_sea_desc options), in the order given */
    int sea_count;              /* pairs in sea */
    uint64_t budget;            /* 0 = the tables' own */
    float sun_elev_deg, sun_azim_deg;
    int camera_given, path;
    struct camera camera;
    int quality, geometry;      /* enum swell_quality, swell_geometry */
    int tier;                   /* enum swell_tier: SWELL_TIER_BEST unless --tier forces one */
    int pixel_lod;              /* --lod pixel */
    int debug_uncovered;        /* --debug uncovered */
    int debug_variants;         /* --debug variants */
    int detile;                 /* --detile: enum swell_detile */
    double scale;               /* --scale: render scale (swell_upscale); 0 = 1 */
    int verbose;
    int bench;                  /* --bench: time frames against the baseline quad */
    int warmup;                 /* --warmup: untimed bench frames; -1 = default */
    const char *results;        /* --results FILE.json */
    const char *scene;          /* --scene: label in the results */
    int boat;                   /* --boat: the demo boat (app/boat.h) */
    float boat_speed_mps, boat_heading_deg;
    const char *mask_path;      /* --mask FILE.png: the waves' amplitude by its grey levels */
    double mask_area[4];        /* --mask-area X0,Y0,W,H: where it lies, m */
    int mask_area_given;
};

/* --out's text: -1 when not a file name or a pattern with one %d, else its %d count (0, 1). */
int options_out_conversions(const char *s);

/* The command line's names of a quality and a geometry ("high", "grid"). */
const char *options_quality_name(int quality);
const char *options_geometry_name(int geometry);

/* Fill o from argv: 0, 2 for a usage error (printed), or exit(0) after --help or --version. */
int options_parse(int argc, char **argv, struct options *o);

#endif
