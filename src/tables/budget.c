/* budget.c - what a table set costs in memory (budget.h). */
#include "tables/budget.h"

#include "tables/tables.h"

static uint64_t rgba8_chain_bytes(int n)
{
    uint64_t b = 0;
    for (;;) {
        b += (uint64_t)n * (uint64_t)n * 4u;
        if (n <= 1)
            return b;
        n /= 2;
    }
}

uint64_t budget_resident_bytes(int patterns, int n_fs)
{
    /* streamed per-pattern slope + whitecap textures (one frame each, full mips) */
    return (uint64_t)patterns * 2u * rgba8_chain_bytes(n_fs) + BUDGET_SIZING_MARGIN_BYTES;
}

uint64_t budget_table_bytes(int patterns, int n_fs, int n_geo, int frames)
{
    struct seastate s = { .patterns = patterns, .size_fs = n_fs, .size_geo = n_geo,
                          .frames = frames };
    struct swell_table shape[SWELL_MAX_TABLES];
    int n = tables_layout(&s, shape);
    uint64_t bytes = 0;
    for (int i = 0; i < n; i++)
        bytes += table_bytes(&shape[i]);
    return bytes;
}

uint64_t budget_sizing_bytes(const struct seastate *s)
{
    return budget_table_bytes(s->patterns, s->size_fs, s->size_geo, s->frames) +
           budget_resident_bytes(s->patterns, s->size_fs);
}

/* The GPU bytes of a set: with blend_sources, the two loop frames per streamed table the GPU
 * blends from too (render/stream_gpu.c). */
static uint64_t gpu_bytes(const struct seastate *s, int blend_sources)
{
    struct swell_table shape[SWELL_MAX_TABLES];
    int n = tables_layout(s, shape);
    uint64_t b = BUDGET_GPU_FIXED_BYTES;
    for (int i = 0; i < n; i++) {
        int layers = shape[i].layers > 0 ? shape[i].layers : 1;
        uint64_t frame = table_bytes(&shape[i]) / (uint64_t)layers;
        if (shape[i].kind == TABLE_SLOPE || shape[i].kind == TABLE_WHITECAP)
            b += (blend_sources ? 3u : 1u) * frame;   /* one loop-blended frame, streamed */
        else if (shape[i].kind == TABLE_DISP)
            b += 2u * frame;    /* vertex texture fetch: the two frames blended */
    }
    return b;
}

uint64_t budget_gpu_bytes(const struct seastate *s)
{
    return gpu_bytes(s, 1);
}

uint64_t budget_gpu_need_bytes(const struct seastate *s)
{
    return gpu_bytes(s, 0);
}

int budget_check(const struct seastate *s, uint64_t budget, const char *what,
                 struct swell_err *err)
{
    if (!budget)
        budget = s->budget_bytes;
    uint64_t tables = budget_sizing_bytes(s);
    if (tables > s->budget_bytes)
        return swell_fail(err, SWELL_E_BUDGET,
                          "%s: %d patterns of %dx%d tables over %d frames take %llu bytes with "
                          "their streamed part, more than the %llu-byte budget the set was baked "
                          "for: the manifest was not written by swell-bake; re-bake the set",
                          what, s->patterns, s->size_fs, s->size_fs, s->frames,
                          (unsigned long long)tables, (unsigned long long)s->budget_bytes);
    uint64_t need = budget_gpu_need_bytes(s);
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
