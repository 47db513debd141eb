/* budget.h - what a table set costs in memory (DESIGN.md "Budgets"; issue 17 item 4).
 *
 * A budget (seastate budget_bytes, swell --budget) bounds the GPU memory the renderer holds for
 * the sea: the streamed textures, the vertex-fetch displacement, the sky and Fresnel textures,
 * the geometry's buffers and, when asked for, the passes' targets and the render-scale target.
 * gl/gpu.h charges each of them before it is made. The bake also sizes the tables (held in
 * RAM and streamed from) by it: tables + streamed + a margin within the budget (bake.c).
 * The display's own frame buffers (the KMS scanout buffers, the surfaceless output frame) are
 * not the sea's: they are reported beside it (swell's memory line), not charged.
 */
#ifndef SWELL_BUDGET_H
#define SWELL_BUDGET_H

#include <stdint.h>

#include "core/err.h"
#include "core/seastate.h"

/* GPU bytes the renderer needs besides what scales with the tables: the sky map (half-float
 * where the device has it), its background table, the Fresnel atlas, the near/far patches'
 * vertex and index buffers (larger than the projected grid's) with the CPU vertex terms, the
 * sky mesh. The largest over every tier, geometry kind and quality at the default grids,
 * measured by tests/frame/test_budget.c, which fails if any combination needs more. */
#define BUDGET_GPU_FIXED_BYTES (3100u * 1024u)

/* What the bake's size choice charges besides the tables' own bytes (bake.c choose_sizes): the
 * streamed per-pattern textures (one frame each, with mips) plus a fixed margin. A sizing rule
 * for the tables held in RAM; the GPU memory is budget_gpu_bytes. */
#define BUDGET_SIZING_MARGIN_BYTES (1536u * 1024u)
uint64_t budget_resident_bytes(int patterns, int n_fs);
/* Bytes of all tables for a configuration (tables_layout). */
uint64_t budget_table_bytes(int patterns, int n_fs, int n_geo, int frames);
/* What the size choice charges for a resolved state: its tables plus budget_resident_bytes. */
uint64_t budget_sizing_bytes(const struct seastate *s);

/* The most GPU memory a renderer takes for a set of this resolved state (its tables_layout:
 * three frames of each slope and whitecap table, the one blended and the two the GPU blends
 * it from (render/stream_gpu.c), two of each displacement table, and the fixed part): every
 * tier, geometry kind and quality at the default grids, no passes. The bake sizes the tables
 * so that it fits the budget. */
uint64_t budget_gpu_bytes(const struct seastate *s);
/* The least it needs: one frame of each slope and whitecap table (the CPU blends, which the
 * renderer falls back to where the budget has no room for the GPU's sources). */
uint64_t budget_gpu_need_bytes(const struct seastate *s);
/* SWELL_E_BUDGET unless budget_gpu_need_bytes(s) fits budget (0: s->budget_bytes) and the tables
 * with the sizing rule's part fit s->budget_bytes (as the bake sized them); the message names
 * what, the bytes and what to do. Checked before anything is read or allocated. */
int budget_check(const struct seastate *s, uint64_t budget, const char *what,
                 struct swell_err *err);

#endif
