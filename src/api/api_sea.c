/* api_sea.c - the public sea (include/swell.h): bake, load, save, describe, and the CPU query
 * over geometry/sea.h. A swell_sea is immutable once made, so queries need no lock. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include "api/api.h"
#include "bake/bake.h"
#include "core/preset.h"
#include "geometry/sea.h"
#include "tables/tables_io.h"

/* An override only where the descriptor names a value (0 keeps the preset's or the default). */
#define SET_IF(field, value) do { if ((value) != 0) (field) = (value); } while (0)

int swell_sea_bake(const swell_sea_desc *desc, swell_sea **out, struct swell_err *err)
{
    swell_sea_desc d0;
    memset(&d0, 0, sizeof d0);
    const swell_sea_desc *d = desc ? desc : &d0;
    if (!out)
        return swell_fail(err, SWELL_E_ARG, "swell_sea_bake: out is NULL");
    *out = NULL;
    struct seastate s;
    memset(&s, 0, sizeof s);
    if (d->preset && preset_load(d->preset, &s, err))
        return err ? err->code : SWELL_E_ARG;
    SET_IF(s.wind_speed_mps, d->wind_speed_mps);
    SET_IF(s.wind_dir_deg, d->wind_dir_deg);
    SET_IF(s.fetch_km, d->fetch_km);
    SET_IF(s.depth_m, d->depth_m);
    SET_IF(s.seed, d->seed);
    SET_IF(s.budget_bytes, d->budget_bytes);
    swell_sea *sea = calloc(1, sizeof *sea);
    if (!sea)
        return swell_fail(err, SWELL_E_NOMEM, "swell_sea_bake: no memory for a sea");
    int rc = swell_bake(&s, NULL, &sea->tables, err);
    if (rc) {
        free(sea);
        return rc;
    }
    *out = sea;
    return SWELL_OK;
}

int swell_sea_load(const char *dir, swell_sea **out, struct swell_err *err)
{
    if (!out || !dir)
        return swell_fail(err, SWELL_E_ARG, "swell_sea_load: dir and out must not be NULL");
    *out = NULL;
    swell_sea *sea = calloc(1, sizeof *sea);
    if (!sea)
        return swell_fail(err, SWELL_E_NOMEM, "swell_sea_load: no memory for a sea");
    int rc = tables_load_dir(dir, &sea->tables, err);
    if (rc) {
        free(sea);
        return rc;
    }
    *out = sea;
    return SWELL_OK;
}

int swell_sea_save(const swell_sea *sea, const char *dir, struct swell_err *err)
{
    if (!sea || !dir)
        return swell_fail(err, SWELL_E_ARG, "swell_sea_save: sea and dir must not be NULL");
    return tables_save_dir(&sea->tables, dir, err);
}

void swell_sea_destroy(swell_sea *sea)
{
    if (!sea)
        return;
    tables_destroy(&sea->tables);
    free(sea);
}

void swell_sea_get_info(const swell_sea *sea, swell_sea_info *out)
{
    memset(out, 0, sizeof *out);
    if (!sea)
        return;
    const struct swell_tables *t = &sea->tables;
    out->wind_speed_mps = t->state.wind_speed_mps;
    out->significant_height_m = t->hs_m;
    out->loop_period_s = t->loop_period_s;
    out->patterns = t->patterns;
    for (int i = 0; i < t->patterns && i < 4; i++)
        out->pattern_size_m[i] = t->pattern[i].size_m;
    out->table_bytes = tables_bytes(t);
}

int swell_sea_sample(const swell_sea *sea, const swell_sample_desc *desc, const double *xy,
                     size_t n, double t_s, swell_sample *out, struct swell_err *err)
{
    if (!sea || (n > 0 && (!xy || !out)))
        return swell_fail(err, SWELL_E_ARG, "swell_sea_sample: sea, xy and out must not be "
                          "NULL");
    double min_wl = desc ? desc->min_wavelength_m : 0.0;
    if (!(min_wl >= 0.0) || !isfinite(min_wl) || !isfinite(t_s))
        return swell_fail(err, SWELL_E_ARG, "swell_sea_sample: min_wavelength_m %g and t_s %g "
                          "must be finite, the wavelength >= 0", min_wl, t_s);
    struct sea_query q;
    sea_query_init(&sea->tables, !(desc && desc->no_detile), min_wl, &q);
    for (size_t i = 0; i < n; i++) {
        double x = xy[2 * i], y = xy[2 * i + 1];
        if (!isfinite(x) || !isfinite(y))
            return swell_fail(err, SWELL_E_ARG, "swell_sea_sample: point %zu (%g, %g) is not "
                              "finite", i, x, y);
        struct sea_point p;
        sea_query_point(&sea->tables, &q, x, y, t_s, &p);
        out[i].height_m = p.height;
        for (int c = 0; c < 3; c++) {
            out[i].displacement[c] = p.disp[c];
            out[i].normal[c] = (float)p.normal[c];
            out[i].velocity[c] = (float)p.velocity[c];
        }
    }
    return SWELL_OK;
}
