/* bake.h - sea state -> tables (DESIGN.md data flow). Deterministic: same resolved sea state,
 * byte-identical tables. Never per frame.
 */
#ifndef SWELL_BAKE_H
#define SWELL_BAKE_H

#include "core/err.h"
#include "core/seastate.h"
#include "tables/tables.h"

struct bake_opts {
    /* called with done in [0, 1] and a stage name; may be NULL */
    void (*progress)(void *user, double done, const char *stage);
    void *user;
};

/* Resolve, validate, choose sizes for the budget (or refuse with SWELL_E_BUDGET saying what is
 * needed), bake every table. `out` is zeroed first; on failure it holds nothing. */
int swell_bake(const struct seastate *state, const struct bake_opts *opts,
               struct swell_tables *out, struct swell_err *err);

/* What the size choice charges besides the tables' own bytes (bake.c choose_sizes): the streamed
 * per-pattern textures (one frame each, with mips) plus a fixed margin. A sizing rule for the
 * tables held in RAM; the renderer's GPU memory is checked on its own (tables/budget.h
 * budget_gpu_bytes, tested against the renderer's accounting by tests/frame/test_budget.c). */
#define SWELL_RENDERER_RESERVE_BYTES (1536u * 1024u)
uint64_t bake_resident_bytes(int patterns, int n_fs);
/* Bytes of all tables for a configuration (what the budget charges besides the resident part). */
uint64_t bake_table_bytes(int patterns, int n_fs, int n_geo, int frames);

#endif
