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
/* swell_bake's checks alone, nothing baked: resolve, validate, the sizes for the budget. */
int bake_check(const struct seastate *state, struct swell_err *err);
int swell_bake(const struct seastate *state, const struct bake_opts *opts,
               struct swell_tables *out, struct swell_err *err);

#endif
