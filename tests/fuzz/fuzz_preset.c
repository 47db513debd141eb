/* fuzz_preset.c - libFuzzer target for preset_parse_memory (src/core/preset.h).
 *
 * Contracts checked beyond "no crash, no leak, no UB":
 *  - a refusal has a code and a message naming the source, and leaves the state unchanged;
 *  - an accepted preset holds no NaN/inf, and round-trips exactly through
 *    preset_format_state -> preset_parse_memory (floats are written %.9g).
 */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "core/err.h"
#include "core/preset.h"
#include "core/seastate.h"
#include "fuzz_common.h"

#define FUZZ_PRESET_NAME "fuzz.preset"

static void default_state(struct seastate *s)
{
    memset(s, 0, sizeof *s);
    seastate_resolve(s);
}

/* Field by field: struct padding is not part of the state. Floats compare bit for bit, so a
 * round trip must keep -0 and every last ulp. */
#define SAME_F(a, b, f) (memcmp(&(a)->f, &(b)->f, sizeof (a)->f) == 0)
static int same_state(const struct seastate *a, const struct seastate *b)
{
    return SAME_F(a, b, wind_speed_mps) && SAME_F(a, b, wind_dir_deg) && SAME_F(a, b, fetch_km) &&
           SAME_F(a, b, depth_m) && a->spectrum == b->spectrum && SAME_F(a, b, spread) &&
           a->seed == b->seed && a->patterns == b->patterns && SAME_F(a, b, loop_period_s) &&
           a->frames == b->frames && a->size_fs == b->size_fs && a->size_geo == b->size_geo &&
           SAME_F(a, b, choppiness) && a->whitecap_model == b->whitecap_model &&
           SAME_F(a, b, foam_half_life_s) && a->budget_bytes == b->budget_bytes;
}

static int all_finite(const struct seastate *s)
{
    return isfinite(s->wind_speed_mps) && isfinite(s->wind_dir_deg) && isfinite(s->fetch_km) &&
           isfinite(s->depth_m) && isfinite(s->spread) && isfinite(s->loop_period_s) &&
           isfinite(s->choppiness) && isfinite(s->foam_half_life_s);
}

static int fuzz_preset_one(const uint8_t *data, size_t size)
{
    struct seastate before, s;
    default_state(&before);
    default_state(&s);
    struct swell_err err;
    swell_err_clear(&err);
    int rc = preset_parse_memory((const char *)data, size, FUZZ_PRESET_NAME, &s, &err);
    if (rc) {
        FUZZ_CHECK_REFUSAL(rc, err);
        FUZZ_CHECK(strstr(err.msg, FUZZ_PRESET_NAME) != NULL, "message names the source");
        FUZZ_CHECK(same_state(&s, &before), "refused preset leaves the state");
        return rc;
    }
    char text[4096];
    size_t len = 0;
    rc = preset_format_state(&s, "", text, sizeof text, &len, &err);
    FUZZ_CHECK(rc == 0, "an accepted state can be formatted");
    FUZZ_CHECK(all_finite(&s), "accepted values are finite");
    struct seastate again;
    default_state(&again);
    rc = preset_parse_memory(text, len, FUZZ_PRESET_NAME, &again, &err);
    FUZZ_CHECK(rc == 0, "the formatted state parses");
    FUZZ_CHECK(same_state(&again, &s), "format -> parse round trip is exact");
    return 0;
}

#ifndef SWELL_FUZZ_NO_ENTRY
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_preset_one(data, size);
    return 0;
}
#endif
