/* api.h - what the public handles hold (include/swell.h): the api layer wraps the library's
 * modules, above every other layer; nothing below includes it. */
#ifndef SWELL_API_INTERNAL_H
#define SWELL_API_INTERNAL_H

#include "swell.h"
#include "gl/gpu.h"
#include "render/renderer.h"
#include "tables/tables.h"

/* text (len bytes) into buf as snprintf writes: at most cap bytes with the terminating 0 (buf
 * may be NULL when cap is 0); returns len, the whole text's length. */
size_t api_text_out(const char *text, size_t len, char *buf, size_t cap);

struct swell_sea {
    struct swell_tables tables;
};

struct swell_ocean {
    const struct swell_sea *sea;
    struct gpu gpu;
    struct renderer *renderer;
    int unit0, units;           /* the texture units it may bind (swell_ocean_desc) */
    int quality;                /* in use: renderer_open may fall back to low */
    char *shader_dir;           /* swell_ocean_desc's, copied; NULL: the installed shaders */
};

#endif
