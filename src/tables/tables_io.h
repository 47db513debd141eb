/* tables_io.h - a table set on disk: one KTX 1.1 file per table (src/tables/ktx.h) plus
 * "manifest.swell" (src/core/kv.h format, first line "swell-manifest 2") holding the resolved sea
 * state, every swell_tables field (floats %.9g, exact round trip) and, per table, its file,
 * kind, pattern, geometry, file size and crc32 of the whole file; its last line,
 * "manifest.crc32 = N", is the crc32 of every line above it ("\r\n" read as "\n"). Each KTX
 * file carries the set's id (tables_set_id: the crc32 of the state lines), so a table from
 * another bake is refused even where a manifest was edited to list it. Every value is checked
 * on load (src/tables/set_check.h), by the loader and `inspect` alike.
 *
 * Crash safety and ownership: a save writes the whole set into a new folder beside dir and
 * swaps it in at once (src/tables/set_dir.h), replacing dir only when it holds nothing but a
 * table set; a killed save leaves dir as it was. Leftover temporary files ("*.tmp.*") are
 * never read.
 */
#ifndef SWELL_TABLES_IO_H
#define SWELL_TABLES_IO_H

#include <stddef.h>
#include <stdint.h>
#include "core/err.h"
#include "tables/tables.h"

#define TABLES_MANIFEST_NAME    "manifest.swell"
#define TABLES_MANIFEST_MAGIC   "swell-manifest"
#define TABLES_MANIFEST_VERSION 5   /* 2: Hu's Fresnel texture indexed by the view angle,
                                       * 3: by a radius denser towards grazing (fresnel.h),
                                       * 4: whitecap tables hold the foam memory of the
                                       *    combined k (bake.c), not per-pattern foam,
                                       * 5: sealed (manifest.crc32), values checked
                                       *    (set_check.h), tables carry swell.set */
#define TABLES_MANIFEST_MAX_BYTES (1u << 20)

struct tables_manifest_entry {
    char name[32];          /* table name; the file is name + ".ktx" */
    int kind, pattern, format, width, height, layers, levels;
    uint64_t file_bytes;    /* size of the KTX file */
    uint32_t file_crc32;    /* zlib crc32 of the whole KTX file */
};

struct tables_manifest {
    struct swell_tables set;   /* every field; set.table[i] has name and geometry, data NULL */
    struct tables_manifest_entry entry[SWELL_MAX_TABLES];  /* set.count of them */
};

/* Create dir (and parents) and write the set as described above. Deterministic bytes. */
int tables_save_dir(const struct swell_tables *t, const char *dir, struct swell_err *err);

/* Load a directory written by tables_save_dir. Every table file is checked against the
 * manifest (present, size, crc32, header agrees) and by the KTX reader; a .ktx file the
 * manifest does not list is refused. All-or-nothing: on failure *out is zeroed. */
int tables_load_dir(const char *dir, struct swell_tables *out, struct swell_err *err);
/* The same, refused before any table is read when the renderer's GPU memory for the set
 * (tables/budget.h) exceeds budget (0: the set's own budget; tables_load_dir). */
int tables_load_dir_within(const char *dir, uint64_t budget, struct swell_tables *out,
                           struct swell_err *err);

/* Per-table result for `swell-bake inspect`. */
struct tables_verify_entry {
    char file[48];          /* "slope_p0.ktx" */
    int listed;             /* 1 if the manifest lists it, 0 for an unlisted .ktx file */
    int kind, pattern, format, width, height, layers, levels;  /* from the manifest */
    uint64_t bytes;         /* file bytes per the manifest (0 when unlisted) */
    int status;             /* SWELL_OK or the SWELL_E_* of the first problem */
    char msg[1024];         /* that problem, "" when ok */
};
typedef void (*tables_verify_fn)(void *user, const struct tables_verify_entry *e);

/* Check every table in dir, calling fn (may be NULL) once per listed table and per unlisted
 * .ktx file. Returns 0 when all are sound, else the first failing code with err holding its
 * message; a missing or malformed manifest fails before any fn call. *manifest_out (may be
 * NULL) receives the manifest. */
int tables_verify_dir(const char *dir, tables_verify_fn fn, void *user,
                      struct tables_manifest *manifest_out, struct swell_err *err);

/* Parse manifest text (fuzz target): the seal, then every value (set_check.h).
 * name_for_errors labels messages. */
int manifest_read_memory(const void *buf, size_t len, const char *name_for_errors,
                         struct tables_manifest *out, struct swell_err *err);

#endif
