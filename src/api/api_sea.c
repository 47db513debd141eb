/* api_sea.c - the public sea (include/swell.h): bake, load, save, describe, and the CPU query
 * over geometry/sea.h. A swell_sea is immutable once made, so queries need no lock. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "api/api.h"
#include "bake/bake.h"
#include "core/datadir.h"
#include "core/preset.h"
#include "tables/budget.h"
#include "geometry/grid.h"
#include "geometry/kelvin.h"
#include "geometry/mask.h"
#include "geometry/sea.h"
#include "tables/tables_io.h"

/* An override only where the descriptor names a value (0 keeps the preset's or the default). */
#define SET_IF(field, value) do { if ((value) != 0) (field) = (value); } while (0)

/* The sea state a descriptor asks for: the preset, the fields that are not 0, then the
 * options in order. */
static int desc_state(const swell_sea_desc *d, struct seastate *s, struct swell_err *err)
{
    int rc;
    memset(s, 0, sizeof *s);
    if (d->preset && (rc = preset_load(d->preset, s, err)))
        return rc;
    SET_IF(s->wind_speed_mps, d->wind_speed_mps);
    SET_IF(s->wind_dir_deg, d->wind_dir_deg);
    SET_IF(s->fetch_km, d->fetch_km);
    SET_IF(s->depth_m, d->depth_m);
    SET_IF(s->seed, d->seed);
    SET_IF(s->budget_bytes, d->budget_bytes);
    for (size_t i = 0; d->options && d->options[i]; i += 2) {
        const char *name = d->options[i], *value = d->options[i + 1];
        if (!value)
            return swell_fail(err, SWELL_E_ARG, "swell_sea_desc options: '%s' has no value "
                              "(options come as name and value pairs ending in NULL)", name);
        if (!strcmp(name, "--preset")) {
            if ((rc = preset_load(value, s, err)))
                return rc;
            continue;
        }
        const struct seastate_field *f = seastate_option(name);
        if (!f)
            return swell_fail(err, SWELL_E_ARG, "swell_sea_desc options: no option '%s' "
                              "(swell_sea_usage lists them)", name);
        if ((rc = seastate_set_option(s, f, value, err)))
            return rc;
    }
    return SWELL_OK;
}

/* what a NULL descriptor asks for: every default */
static const swell_sea_desc zero_desc;

int swell_sea_bake(const swell_sea_desc *desc, swell_sea **out, struct swell_err *err)
{
    const swell_sea_desc *d = desc ? desc : &zero_desc;
    if (!out)
        return swell_fail(err, SWELL_E_ARG, "swell_sea_bake: out is NULL");
    *out = NULL;
    struct seastate s;
    int rc = desc_state(d, &s, err);
    if (rc)
        return rc;
    swell_sea *sea = calloc(1, sizeof *sea);
    if (!sea)
        return swell_fail(err, SWELL_E_NOMEM, "swell_sea_bake: no memory for a sea");
    struct bake_opts bo = { .progress = d->progress, .user = d->progress_user };
    rc = swell_bake(&s, &bo, &sea->tables, err);
    if (rc) {
        free(sea);
        return rc;
    }
    *out = sea;
    return SWELL_OK;
}

size_t api_text_out(const char *text, size_t len, char *buf, size_t cap)
{
    if (cap) {
        size_t n = len < cap - 1 ? len : cap - 1;
        memcpy(buf, text, n);
        buf[n] = '\0';
    }
    return len;
}

int swell_sea_check(const swell_sea_desc *desc, struct swell_err *err)
{
    struct seastate s;
    int rc = desc_state(desc ? desc : &zero_desc, &s, err);
    return rc ? rc : bake_check(&s, err);
}

int swell_sea_option(const char *name)
{
    return name && (!strcmp(name, "--preset") || seastate_option(name) != NULL);
}

size_t swell_sea_usage(int what, char *buf, size_t cap)
{
    char *text = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    if (!f) {
        if (cap)
            buf[0] = '\0';
        return 0;
    }
    if (what == SWELL_USAGE_DATA)
        data_dir_usage(f);
    else
        seastate_usage(f, what == SWELL_USAGE_TABLES);
    fclose(f);
    api_text_out(text, len, buf, cap);
    free(text);
    return len;
}

int swell_sea_load_budget(const char *dir, uint64_t budget_bytes, swell_sea **out,
                          struct swell_err *err)
{
    if (!out || !dir)
        return swell_fail(err, SWELL_E_ARG, "swell_sea_load: dir and out must not be NULL");
    *out = NULL;
    const struct seastate_field *bf = seastate_option("--budget");   /* its range, once */
    if (budget_bytes && (budget_bytes < bf->lo || budget_bytes > bf->hi))
        return swell_fail(err, SWELL_E_ARG, "swell_sea_load_budget: budget %llu bytes is out "
                          "of range (%.0f to %.0f MiB, or 0 for the set's own)",
                          (unsigned long long)budget_bytes, bf->lo / 1048576.0,
                          bf->hi / 1048576.0);
    swell_sea *sea = calloc(1, sizeof *sea);
    if (!sea)
        return swell_fail(err, SWELL_E_NOMEM, "swell_sea_load: no memory for a sea");
    int rc = tables_load_dir_within(dir, budget_bytes, &sea->tables, err);
    if (rc) {
        free(sea);
        return rc;
    }
    if (budget_bytes)   /* what its oceans keep within (swell_ocean_create) */
        sea->tables.state.budget_bytes = budget_bytes;
    *out = sea;
    return SWELL_OK;
}

int swell_sea_load(const char *dir, swell_sea **out, struct swell_err *err)
{
    return swell_sea_load_budget(dir, 0, out, err);
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

/* A set's description (its sea state and what the bake measured) into out. */
static void tables_info(const struct swell_tables *t, swell_sea_info *out)
{
    memset(out, 0, sizeof *out);
    out->wind_speed_mps = t->state.wind_speed_mps;
    out->significant_height_m = t->hs_m;
    out->loop_period_s = t->loop_period_s;
    out->patterns = t->patterns;
    for (int i = 0; i < t->patterns && i < 4; i++) {
        out->pattern_size_m[i] = t->pattern[i].size_m;
        out->mss_resolved[0] += t->pattern[i].mss_x;
        out->mss_resolved[1] += t->pattern[i].mss_y;
    }
    out->table_bytes = tables_bytes(t);
    out->spectrum = spectrum_name(t->state.spectrum);
    out->wind_dir_deg = t->state.wind_dir_deg;
    out->fetch_km = t->state.fetch_km;
    out->depth_m = t->state.depth_m;
    out->seed = t->state.seed;
    out->frames = t->frames;
    out->table_size = t->state.size_fs;
    out->geometry_size = t->state.size_geo;
    out->mss_unresolved[0] = t->mss_unresolved_x;
    out->mss_unresolved[1] = t->mss_unresolved_y;
    out->whitecap_epsilon = t->whitecap_epsilon;
    out->whitecap_breaking_fraction = t->whitecap_breaking_fraction;
    out->foam_recovery_per_s = t->foam_recovery_per_s;
    out->whitecap_model = whitecap_model_name(t->state.whitecap_model);
    out->whitecap_fraction_model = t->whitecap_fraction_model;
    out->whitecap_fraction_measured = t->whitecap_fraction_measured;
    out->resident_bytes = budget_resident_bytes(t->patterns, t->state.size_fs);
    out->gpu_bytes_max = budget_gpu_bytes(&t->state);
    out->budget_bytes = t->state.budget_bytes;
    out->tables = t->count;
}

void swell_sea_get_info(const swell_sea *sea, swell_sea_info *out)
{
    memset(out, 0, sizeof *out);
    if (sea)
        tables_info(&sea->tables, out);
}

int swell_sea_get_table(const swell_sea *sea, int i, swell_table_info *out,
                        struct swell_err *err)
{
    if (!sea || !out || i < 0 || i >= sea->tables.count)
        return swell_fail(err, SWELL_E_ARG, "swell_sea_get_table: no table %d (the sea has %d; "
                          "sea and out must not be NULL)", i, sea ? sea->tables.count : 0);
    const struct swell_table *t = &sea->tables.table[i];
    memset(out, 0, sizeof *out);
    snprintf(out->name, sizeof out->name, "%s", t->name);
    out->kind = table_kind_name(t->kind);
    out->format = table_format_name(t->format);
    out->pattern = t->pattern;
    out->width = t->width;
    out->height = t->height;
    out->layers = t->layers;
    out->levels = t->levels;
    out->bytes = table_bytes(t);
    return SWELL_OK;
}

struct check_ctx {
    swell_table_check_fn fn;
    void *user;
};

static void check_row(void *user, const struct tables_verify_entry *e)
{
    const struct check_ctx *c = user;
    swell_table_info ti;
    memset(&ti, 0, sizeof ti);
    snprintf(ti.name, sizeof ti.name, "%s", e->file);
    ti.kind = e->listed ? table_kind_name(e->kind) : "?";
    ti.format = e->listed ? table_format_name(e->format) : "?";
    ti.pattern = e->pattern;
    ti.width = e->width;
    ti.height = e->height;
    ti.layers = e->layers;
    ti.levels = e->levels;
    ti.bytes = e->bytes;
    c->fn(c->user, &ti, e->listed, e->status, e->msg);
}

int swell_sea_check_dir(const char *dir, swell_table_check_fn fn, void *user,
                        swell_sea_info *info, struct swell_err *err)
{
    if (info)
        memset(info, 0, sizeof *info);
    if (!dir)
        return swell_fail(err, SWELL_E_ARG, "swell_sea_check_dir: dir is NULL");
    struct tables_manifest *m = calloc(1, sizeof *m);
    if (!m)
        return swell_fail(err, SWELL_E_NOMEM, "swell_sea_check_dir: no memory for a manifest");
    struct check_ctx c = { fn, user };
    struct swell_err e2 = { 0 };
    int rc = tables_verify_dir(dir, fn ? check_row : NULL, &c, m, err ? err : &e2);
    /* the manifest was read when it listed tables, sound or not */
    if (info && (rc == SWELL_OK || m->set.count > 0)) {
        tables_info(&m->set, info);
        uint64_t files = 0;
        for (int i = 0; i < m->set.count; i++)
            files += m->entry[i].file_bytes;
        info->table_bytes = files;
    }
    free(m);
    return rc;
}

/* swell_sample_desc's wake: the hull's frame and Bruneton eq. 2's weight of its longest
 * (transverse) wave, 2 pi U^2 / g, under min_wavelength_m (as sea_query_init weighs a
 * pattern's band). weight 0: no wake. */
struct sample_wake {
    struct kelvin_desc k;
    double pos[2], fwd[2];
    float weight;
};

static int sample_wake_init(const swell_sea *sea, const swell_wake *w, double min_wl,
                            struct sample_wake *out, struct swell_err *err)
{
    memset(out, 0, sizeof *out);
    if (!w || w->speed_mps == 0.0f)
        return 0;
    if (!isfinite(w->position_m[0]) || !isfinite(w->position_m[1]) || !isfinite(w->heading_deg))
        return swell_fail(err, SWELL_E_ARG, "swell_sea_sample: the wake's position (%g, %g) m "
                          "and heading %g deg must be finite", w->position_m[0],
                          w->position_m[1], (double)w->heading_deg);
    out->k.speed_mps = w->speed_mps;
    out->k.hull_length_m = w->hull_length_m;
    out->k.beam_m = w->beam_m;
    /* the foam is not returned; the sea's half-life, held within kelvin_check's range */
    out->k.foam_half_life_s = fmin(fmax(sea->tables.state.foam_half_life_s, 0.05), 60.0);
    kelvin_desc_defaults(&out->k);
    int rc = kelvin_check(&out->k, err);
    if (rc)
        return swell_err_context(err, "swell_sea_sample"), rc;
    double hd = w->heading_deg * M_PI / 180.0;
    out->pos[0] = w->position_m[0];
    out->pos[1] = w->position_m[1];
    out->fwd[0] = cos(hd);
    out->fwd[1] = sin(hd);
    double lt = 2.0 * M_PI * out->k.speed_mps * out->k.speed_mps / 9.81;
    out->weight = min_wl > 0.0 ? grid_filter_weight(GRID_FILTER_NMIN, GRID_FILTER_NMAX,
                                                    (float)(lt * GRID_FILTER_NMIN / min_wl))
                               : 1.0f;
    return 0;
}

/* The wake at world (x, y) added to sample o (p: the sea's alone): the height, the normal
 * from the summed slopes, the height's rate d eta / dt = -U d eta / dx_hull (the pattern
 * stands still in the hull's frame, which moves at U along fwd). */
static void sample_wake_add(const struct sample_wake *w, double x, double y, int height_only,
                            const struct sea_point *p, swell_sample *o)
{
    double dx = x - w->pos[0], dy = y - w->pos[1], f0 = w->fwd[0], f1 = w->fwd[1];
    struct kelvin_sample s;
    kelvin_eval(&w->k, dx * f0 + dy * f1, dy * f0 - dx * f1, &s);
    double a = w->weight;
    o->height_m += a * s.eta;
    o->displacement[2] += a * s.eta;
    if (height_only)
        return;
    /* the sea's slope from its normal, plus the wake's in world axes */
    double nz = p->normal[2] > 1e-6 ? p->normal[2] : 1e-6;
    double sx = -p->normal[0] / nz + a * (s.slope[0] * f0 - s.slope[1] * f1);
    double sy = -p->normal[1] / nz + a * (s.slope[0] * f1 + s.slope[1] * f0);
    double len = sqrt(sx * sx + sy * sy + 1.0);
    o->normal[0] = (float)(-sx / len);
    o->normal[1] = (float)(-sy / len);
    o->normal[2] = (float)(1.0 / len);
    o->velocity[2] += (float)(-a * w->k.speed_mps * s.slope[0]);
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
    q.height_only = desc && desc->height_only;
    struct sample_wake wk;
    int rc = sample_wake_init(sea, desc ? desc->wake : NULL, min_wl, &wk, err);
    if (rc)
        return rc;
    const swell_mask *sm = desc ? desc->mask : NULL;
    struct wave_mask mask;
    if (sm && (rc = wave_mask_init(&mask, "swell_sea_sample", sm->amplitude, sm->width,
                                   sm->height, sm->origin_m, sm->size_m, err)))
        return rc;
    for (size_t i = 0; i < n; i++) {
        double x = xy[2 * i], y = xy[2 * i + 1];
        if (!isfinite(x) || !isfinite(y))
            return swell_fail(err, SWELL_E_ARG, "swell_sea_sample: point %zu (%g, %g) is not "
                              "finite", i, x, y);
        struct sea_point p;
        /* the mask's amplitude at (x, y) scales every pattern's displacement (mask.h; the
         * drawn vertex takes it at its rest point, within a coarse mask's texel of here) */
        float a = sm ? wave_mask_at(&mask, x, y) : 1.0f;
        if (a != 1.0f) {
            struct sea_query qa = q;
            for (int k = 0; k < SWELL_MAX_PATTERNS; k++)
                qa.weight[k] *= a;
            sea_query_point(&sea->tables, &qa, x, y, t_s, &p);
        } else {
            sea_query_point(&sea->tables, &q, x, y, t_s, &p);
        }
        out[i].height_m = p.height;
        for (int c = 0; c < 3; c++) {
            out[i].displacement[c] = p.disp[c];
            out[i].normal[c] = (float)p.normal[c];
            out[i].velocity[c] = (float)p.velocity[c];
        }
        if (wk.weight > 0.0f)
            sample_wake_add(&wk, x, y, q.height_only, &p, &out[i]);
    }
    return SWELL_OK;
}
