/* budget.c - what a table set costs in memory (budget.h). */
#include "tables/budget.h"

#include "tables/tables.h"

uint64_t budget_gpu_bytes(const struct seastate *s)
{
    struct swell_table shape[SWELL_MAX_TABLES];
    int n = tables_layout(s, shape);
    uint64_t b = BUDGET_GPU_FIXED_BYTES;
    for (int i = 0; i < n; i++) {
        int layers = shape[i].layers > 0 ? shape[i].layers : 1;
        uint64_t frame = table_bytes(&shape[i]) / (uint64_t)layers;
        if (shape[i].kind == TABLE_SLOPE || shape[i].kind == TABLE_WHITECAP)
            b += frame;         /* one loop-blended frame, streamed */
        else if (shape[i].kind == TABLE_DISP)
            b += 2u * frame;    /* vertex texture fetch: the two frames blended */
    }
    return b;
}

int budget_check(const struct seastate *s, uint64_t budget, const char *what,
                 struct swell_err *err)
{
    if (!budget)
        budget = s->budget_bytes;
    uint64_t need = budget_gpu_bytes(s);
    if (need <= budget)
        return SWELL_OK;
    return swell_fail(err, SWELL_E_BUDGET,
                      "%s: the renderer needs up to %llu bytes of GPU memory for %d patterns of "
                      "%dx%d tables (%dx%d displacement) but the budget is %llu bytes: use "
                      "--budget %llu or more, or tables baked for this budget",
                      what, (unsigned long long)need, s->patterns, s->size_fs, s->size_fs,
                      s->size_geo, s->size_geo, (unsigned long long)budget,
                      (unsigned long long)need);
}
