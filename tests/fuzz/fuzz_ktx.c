/* fuzz_ktx.c - libFuzzer target for ktx_read_memory (src/tables/ktx.h: "safe on arbitrary input").
 *
 * Contracts checked beyond "no crash, no leak, no UB":
 *  - a refusal has a code and a message naming the file, and leaves *out zeroed;
 *  - an accepted table is self-consistent (geometry within the header limits, data present)
 *    and survives ktx_write_memory -> ktx_read_memory unchanged (same fields, same bytes).
 */
#include <stdint.h>
#include <string.h>

#include "core/err.h"
#include "tables/ktx.h"
#include "tables/tables.h"
#include "fuzz_common.h"

#define FUZZ_KTX_NAME "fuzz.ktx"

static int is_zeroed(const struct swell_table *t)
{
    static const struct swell_table zero;
    return memcmp(t, &zero, sizeof zero) == 0;
}

static int fuzz_ktx_one(const uint8_t *data, size_t size)
{
    struct swell_table t;
    struct swell_err err;
    swell_err_clear(&err);
    int rc = ktx_read_memory(data, size, FUZZ_KTX_NAME, &t, &err);
    if (rc) {
        FUZZ_CHECK_REFUSAL(rc, err);
        FUZZ_CHECK(strstr(err.msg, FUZZ_KTX_NAME) != NULL, "message names the file");
        FUZZ_CHECK(is_zeroed(&t), "refused table is zeroed");
        return rc;
    }
    FUZZ_CHECK(t.data != NULL, "accepted table owns data");
    FUZZ_CHECK(t.width >= 1 && t.width <= KTX_MAX_DIM && t.height >= 1 &&
               t.height <= KTX_MAX_DIM, "dimensions within KTX_MAX_DIM");
    FUZZ_CHECK(t.layers >= 1 && t.layers <= KTX_MAX_LAYERS, "layers within limit");
    FUZZ_CHECK(t.kind >= 0 && t.kind < TABLE_KIND_COUNT, "kind valid");
    FUZZ_CHECK(t.format >= 0 && t.format < FORMAT_COUNT, "format valid");

    uint8_t *again = NULL;
    size_t again_len = 0;
    rc = ktx_write_memory(&t, &again, &again_len, &err);
    FUZZ_CHECK(rc == 0, "an accepted table can be written back");
    struct swell_table u;
    rc = ktx_read_memory(again, again_len, FUZZ_KTX_NAME, &u, &err);
    FUZZ_CHECK(rc == 0, "the written-back table is accepted");
    FUZZ_CHECK(strcmp(u.name, t.name) == 0 && u.kind == t.kind && u.pattern == t.pattern &&
               u.format == t.format && u.width == t.width && u.height == t.height &&
               u.layers == t.layers && u.levels == t.levels, "round trip keeps the geometry");
    FUZZ_CHECK(memcmp(u.scale, t.scale, sizeof t.scale) == 0 &&
               memcmp(u.bias, t.bias, sizeof t.bias) == 0, "round trip keeps scale and bias");
    FUZZ_CHECK(memcmp(u.data, t.data, table_bytes(&t)) == 0, "round trip keeps the texels");
    free(u.data);
    free(again);
    free(t.data);
    return 0;
}

#ifndef SWELL_FUZZ_NO_ENTRY
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_ktx_one(data, size);
    return 0;
}
#endif
