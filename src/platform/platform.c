/* platform.c - picks a back-end (platform.h) and forwards to it. */
#include "platform/platform.h"

#include <stddef.h>

static const char *const kind_names[PLATFORM_COUNT] = { "auto", "surfaceless", "kms" };

const char *platform_kind_name(int kind)
{
    if (kind < 0 || kind >= PLATFORM_COUNT)
        return "?";
    return kind_names[kind];
}

static int open_backend(const struct platform_backend *be, const struct platform_desc *d,
                        struct platform_handle *h, struct swell_err *err)
{
    int rc = be->create(d, &h->p, err);
    if (rc)
        return rc;
    h->be = be;
    return SWELL_OK;
}

int platform_open(const struct platform_desc *d, struct platform_handle *h, struct swell_err *err)
{
    h->be = NULL;
    h->p = NULL;
    switch (d->kind) {
    case PLATFORM_SURFACELESS:
        return open_backend(&platform_surfaceless_backend, d, h, err);
    case PLATFORM_KMS:
        return open_backend(&platform_kms_backend, d, h, err);
    case PLATFORM_AUTO: {
        /* platform.h: KMS when a connected display exists. The KMS back-end answers
         * SWELL_E_UNSUPPORTED when there is none (or it is not built); any other failure is a
         * real error on a machine that has a display, and is reported rather than hidden. */
        int rc = open_backend(&platform_kms_backend, d, h, err);
        if (rc != SWELL_E_UNSUPPORTED)
            return rc;
        swell_err_clear(err);
        return open_backend(&platform_surfaceless_backend, d, h, err);
    }
    default:
        return swell_fail(err, SWELL_E_ARG, "platform: kind %d is not auto, surfaceless or kms",
                          d->kind);
    }
}

void platform_close(struct platform_handle *h)
{
    if (!h)
        return;
    if (h->be && h->p)
        h->be->destroy(h->p);
    h->be = NULL;
    h->p = NULL;
}
