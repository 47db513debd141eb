/* fuzz_set.c - libFuzzer target for what swell does with a loaded table set's values (issue 17
 * item 7): the manifest's seal and value checks (fuzz_manifest) guard the loader; this target
 * follows an accepted manifest into the CPU side of the renderer.
 *
 * The input is a manifest, read resealed (manifest_reseal) so mutations reach the value checks.
 * When it is accepted, its tables are baked from its own state (one set cached; states bigger
 * than 32x32 texels, 8 frames are not baked, to keep each input fast) - the tables a loader would
 * accept with it, since they must be baked from that state (swell.set) - and the set, with the
 * manifest's statistics and pattern values as they are, is drawn on the CPU: the projected grid
 * and the near/far patches for three cameras (gles2-min's vertex work, every pattern resolved
 * per vertex), and the CPU query at three points.
 *
 * Contracts beyond "no crash, no leak, no UB": every vertex value and every query result finite.
 */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "bake/bake.h"
#include "core/camera.h"
#include "core/err.h"
#include "geometry/grid.h"
#include "geometry/sea.h"
#include "tables/set_check.h"
#include "tables/tables.h"
#include "tables/tables_io.h"
#include "fuzz_common.h"

#define FUZZ_SET_NAME "fuzz/set/manifest.swell"

/* The tables of the last state baked, and its id. */
static struct swell_tables set_base;
static uint32_t set_base_id;
static int set_base_ok;

static int set_bake_for(const struct seastate *state)
{
    uint32_t id = tables_set_id(state);
    if (set_base_ok && id == set_base_id)
        return 1;
    tables_destroy(&set_base);
    set_base_ok = 0;
    if ((long)state->size_fs * state->size_fs * state->frames * state->patterns > 32L * 32 * 8 * 4)
        return 0;
    struct swell_err err;
    swell_err_clear(&err);
    if (swell_bake(state, NULL, &set_base, &err) != 0)
        return 0;
    set_base_id = id;
    set_base_ok = 1;
    return 1;
}

static void check_finite(const float *v, size_t n, const char *what)
{
    for (size_t i = 0; i < n; i++)
        FUZZ_CHECK(isfinite(v[i]), what);
}

static void draw_on_cpu(const struct swell_tables *t)
{
    static const double pose[3][3] = { { 10.0, -10.0, 0.0 }, { 2.0, 3.0, 1.3 },
                                       { 3000.0, -60.0, 7.9 } };   /* altitude, pitch, time */
    for (int kind = 0; kind < 2; kind++) {
        struct grid_desc d = { .tables = t, .kind = kind, .w = 32, .h = 24,
                               .cpu_patterns = (1u << t->patterns) - 1u };
        struct grid *g = NULL;
        struct swell_err err;
        swell_err_clear(&err);
        if (grid_create(&d, &g, &err) != 0) {
            FUZZ_CHECK_REFUSAL(err.code, err);
            continue;
        }
        size_t n = (size_t)grid_vertex_count(g) * GRID_FLOATS;
        float *verts = malloc(n * sizeof *verts);
        FUZZ_CHECK(verts != NULL, "allocate the vertices");
        for (int p = 0; p < 3; p++) {
            struct camera c;
            struct camera_frame view;
            camera_defaults(&c);
            c.pos[2] = (float)pose[p][0];
            c.pitch_deg = (float)pose[p][1];
            camera_frame_make(&c, 64, 36, &view);
            int idx = grid_update(g, &view, pose[p][2], verts);
            FUZZ_CHECK(idx >= 0 && idx <= grid_index_count(g), "index count within the grid");
            check_finite(verts, n, "grid vertices finite");
        }
        free(verts);
        grid_destroy(g);
    }
    struct sea_query q;
    sea_query_init(t, 1, 0.0, &q);
    for (int p = 0; p < 3; p++) {
        struct sea_point sp;
        sea_query_point(t, &q, 17.0 * p - 5.0, 3.5 * p, 1.7 * p, &sp);
        FUZZ_CHECK(isfinite(sp.height) && isfinite(sp.normal[0]) && isfinite(sp.normal[1]) &&
                   isfinite(sp.normal[2]) && isfinite(sp.velocity[2]), "query finite");
    }
}

static int fuzz_set_one(const uint8_t *data, size_t size)
{
    char *text = NULL;
    size_t n = fuzz_resealed(data, size, &text);
    struct tables_manifest *m = malloc(sizeof *m);
    FUZZ_CHECK(m != NULL, "allocate the manifest");
    struct swell_err err;
    swell_err_clear(&err);
    int rc = n ? manifest_read_memory(text, n, FUZZ_SET_NAME, m, &err) : SWELL_E_FORMAT;
    if (rc == 0 && set_bake_for(&m->set.state)) {
        /* the manifest's values with the tables a loader would take with them */
        struct swell_tables t = m->set;
        FUZZ_CHECK(t.count == set_base.count, "the layout is the state's");
        for (int i = 0; i < t.count; i++)
            t.table[i] = set_base.table[i];
        draw_on_cpu(&t);
    } else if (rc && n) {
        FUZZ_CHECK_REFUSAL(rc, err);
    }
    free(m);
    free(text);
    return rc;
}

#ifndef SWELL_FUZZ_NO_ENTRY
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_set_one(data, size);
    return 0;
}
#endif
