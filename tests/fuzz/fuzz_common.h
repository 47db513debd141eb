/* fuzz_common.h - shared by the libFuzzer targets and by tests/unit/test_fuzz_replay.c.
 *
 * Each target file defines `static int fuzz_<target>_one(const uint8_t *, size_t)` returning the
 * loader's result code (0 accepted, SWELL_E_* refused) and, unless SWELL_FUZZ_NO_ENTRY is
 * defined, libFuzzer's LLVMFuzzerTestOneInput. The replay driver includes the target files with
 * SWELL_FUZZ_NO_ENTRY so one ordinary program runs all three.
 *
 * FUZZ_CHECK states a contract of the loader (err.h, ktx.h, tables_io.h, preset.h): a violated
 * contract aborts, which libFuzzer records as a crash and the replay test as a failure.
 */
#ifndef SWELL_FUZZ_COMMON_H
#define SWELL_FUZZ_COMMON_H

#include <stdio.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include "tables/set_check.h"

#define FUZZ_CHECK(cond, what)                                                         \
    do {                                                                               \
        if (!(cond)) {                                                                 \
            fprintf(stderr, "%s:%d: contract violated: %s (%s)\n", __FILE__, __LINE__, \
                    what, #cond);                                                      \
            abort();                                                                   \
        }                                                                              \
    } while (0)

/* Every refusal carries a specific message (STYLE.md habit 6): a code and non-empty text. */
#define FUZZ_CHECK_REFUSAL(rc, err)                                                    \
    do {                                                                               \
        FUZZ_CHECK((rc) > 0 && (rc) < SWELL_ERR_COUNT, "refusal code in range");       \
        FUZZ_CHECK((err).code == (rc), "err.code equals the returned code");           \
        FUZZ_CHECK((err).msg[0] != '\0', "refusal has a message");                     \
    } while (0)

/* A copy of a manifest input sealed again (set_check.h manifest_reseal) in *text (free it);
 * the sealed length, 0 when the input does not end with a newline. */
static inline size_t fuzz_resealed(const uint8_t *data, size_t size, char **text)
{
    *text = malloc(size + 64);
    FUZZ_CHECK(*text != NULL, "allocate the resealed copy");
    if (size)
        memcpy(*text, data, size);
    return manifest_reseal(*text, size, size + 64);
}

#endif
