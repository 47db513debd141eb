/* fuzz_manifest.c - libFuzzer target for manifest_read_memory (src/tables/tables_io.h).
 *
 * Contracts checked beyond "no crash, no leak, no UB":
 *  - a refusal has a code and a message naming the file, and leaves *out zeroed;
 *  - an accepted manifest is within the limits the loader promises (count, patterns, names
 *    unique, geometry positive) so tables_load_dir can index with it safely.
 * Each input is read twice: as it is (the seal refuses nearly every mutation) and resealed
 * (manifest_reseal), so mutations reach the value checks of src/tables/set_check.c too.
 */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/err.h"
#include "tables/tables.h"
#include "tables/set_check.h"
#include "tables/tables_io.h"
#include "fuzz_common.h"

#define FUZZ_MANIFEST_NAME "fuzz/manifest.swell"

static int fuzz_manifest_read(const uint8_t *data, size_t size)
{
    /* ~30 KiB: static would be a file-static mutable singleton, so heap it per call. */
    struct tables_manifest *m = malloc(sizeof *m);
    FUZZ_CHECK(m != NULL, "allocate the manifest");
    struct swell_err err;
    swell_err_clear(&err);
    int rc = manifest_read_memory(data, size, FUZZ_MANIFEST_NAME, m, &err);
    if (rc) {
        FUZZ_CHECK_REFUSAL(rc, err);
        FUZZ_CHECK(strstr(err.msg, FUZZ_MANIFEST_NAME) != NULL, "message names the file");
        struct tables_manifest *zero = calloc(1, sizeof *zero);
        FUZZ_CHECK(zero != NULL, "allocate the reference");
        FUZZ_CHECK(memcmp(m, zero, sizeof *m) == 0, "refused manifest is zeroed");
        free(zero);
        free(m);
        return rc;
    }
    const struct swell_tables *s = &m->set;
    FUZZ_CHECK(s->count >= 0 && s->count <= SWELL_MAX_TABLES, "count within SWELL_MAX_TABLES");
    FUZZ_CHECK(s->patterns >= 0 && s->patterns <= SWELL_MAX_PATTERNS, "patterns within limit");
    for (int i = 0; i < s->count; i++) {
        const struct swell_table *t = &s->table[i];
        FUZZ_CHECK(memchr(t->name, '\0', sizeof t->name) != NULL, "name terminated");
        FUZZ_CHECK(t->data == NULL, "manifest tables own no data");
        FUZZ_CHECK(t->width >= 1 && t->height >= 1 && t->layers >= 1 && t->levels >= 1,
                   "geometry positive");
        FUZZ_CHECK(t->kind >= 0 && t->kind < TABLE_KIND_COUNT, "kind valid");
        FUZZ_CHECK(t->format >= 0 && t->format < FORMAT_COUNT, "format valid");
        for (int j = 0; j < i; j++)
            FUZZ_CHECK(strcmp(s->table[j].name, t->name) != 0, "names unique");
    }
    free(m);
    return 0;
}

/* The result of the resealed input (the raw one's contracts checked too). */
static int fuzz_manifest_one(const uint8_t *data, size_t size)
{
    int raw = fuzz_manifest_read(data, size);
    char *text = NULL;
    size_t n = fuzz_resealed(data, size, &text);
    int rc = n ? fuzz_manifest_read((const uint8_t *)text, n) : raw;
    free(text);
    return rc;
}

#ifndef SWELL_FUZZ_NO_ENTRY
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_manifest_one(data, size);
    return 0;
}
#endif
