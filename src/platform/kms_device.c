/* kms_device.c - what the KMS back-end drives (kms_internal.h): the DRM device (--device, else
 * the first primary node with a connected connector), the connector (--connector by name, else
 * the first connected one), a CRTC for it (the one already driving it when there is one, so no
 * other output loses its CRTC), the mode (preferred; else exact, else nearest) and, for atomic
 * modesetting, the primary plane on that CRTC and the property ids a commit names.
 *
 * Errors list what was found (connectors and their state, available modes) so that the next
 * --connector or --mode can be picked from the message. No display at all is
 * SWELL_E_UNSUPPORTED, so that `auto` falls back to surfaceless (platform.c).
 */
#include "platform/kms_internal.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include <xf86drm.h>
#include <xf86drmMode.h>

#define MAX_DRM_DEVICES 16

static const char *conn_status(drmModeConnection c)
{
    return c == DRM_MODE_CONNECTED ? "connected"
         : c == DRM_MODE_DISCONNECTED ? "disconnected" : "unknown";
}

void kms_connector_name(const drmModeConnector *c, char *buf, size_t n)
{
    const char *t = drmModeGetConnectorTypeName(c->connector_type);
    snprintf(buf, n, "%s-%u", t ? t : "Unknown", c->connector_type_id);
}

/* ---- device and connector ------------------------------------------------------------------ */

/* The connector to drive on fd: desc->connector by name, else the first connected one.
 * Returns it (caller frees) or NULL with `why` filled. */
static drmModeConnector *find_connector(int fd, const char *want, char *why, size_t why_n)
{
    drmModeRes *res = drmModeGetResources(fd);
    if (!res) {
        snprintf(why, why_n, "not a KMS device (drmModeGetResources: %s)", strerror(errno));
        return NULL;
    }
    drmModeConnector *found = NULL;
    size_t used = 0;
    why[0] = '\0';
    used += (size_t)snprintf(why, why_n, "connectors:");
    for (int i = 0; i < res->count_connectors && !found; i++) {
        drmModeConnector *c = drmModeGetConnector(fd, res->connectors[i]);
        if (!c)
            continue;
        char name[64];
        kms_connector_name(c, name, sizeof name);
        if (used < why_n)
            used += (size_t)snprintf(why + used, why_n - used, " %s (%s)", name,
                                     conn_status(c->connection));
        int name_ok = !want || strcmp(want, name) == 0;
        if (name_ok && c->connection == DRM_MODE_CONNECTED && c->count_modes > 0)
            found = c;
        else
            drmModeFreeConnector(c);
    }
    if (!found && res->count_connectors == 0)
        snprintf(why, why_n, "no connectors");
    drmModeFreeResources(res);
    return found;
}

static int open_device(struct platform *p, const char *path, struct swell_err *err)
{
    p->fd = open(path, O_RDWR | O_CLOEXEC);
    if (p->fd < 0) {
        int e = errno;
        return swell_fail(err, SWELL_E_DRM, "platform kms: cannot open %s: %s%s%s", path,
                          strerror(e), (e == EACCES || e == EPERM) ? "; " : "",
                          (e == EACCES || e == EPERM) ? "add yourself to the 'video' group or "
                          NO_HINT_MASTER : "");
    }
    snprintf(p->device, sizeof p->device, "%s", path);
    return SWELL_OK;
}

/* desc->device, else the first primary node (/dev/dri/cardN) with a usable connector. */
int kms_pick_device(struct platform *p, const struct platform_desc *d,
                    drmModeConnector **conn, struct swell_err *err)
{
    char why[768];
    if (d->device) {
        int rc = open_device(p, d->device, err);
        if (rc)
            return rc;
        *conn = find_connector(p->fd, d->connector, why, sizeof why);
        if (!*conn)
            return swell_fail(err, SWELL_E_DRM, "platform kms: no connected connector%s%s%s "
                              "with modes on %s (%s); plug a display in or pick another "
                              "--connector", d->connector ? " named '" : "",
                              d->connector ? d->connector : "", d->connector ? "'" : "",
                              d->device, why);
        return SWELL_OK;
    }
    drmDevicePtr devs[MAX_DRM_DEVICES];
    int n = drmGetDevices2(0, devs, MAX_DRM_DEVICES);
    int primaries = 0;
    char tried[1024];
    size_t used = 0;
    tried[0] = '\0';
    for (int i = 0; i < (n > 0 ? n : 0) && p->fd < 0; i++) {
        if (!(devs[i]->available_nodes & (1 << DRM_NODE_PRIMARY)))
            continue;
        const char *path = devs[i]->nodes[DRM_NODE_PRIMARY];
        primaries++;
        int fd = open(path, O_RDWR | O_CLOEXEC);
        if (fd < 0) {
            if (used < sizeof tried)
                used += (size_t)snprintf(tried + used, sizeof tried - used, "%s%s: %s",
                                         used ? "; " : "", path, strerror(errno));
            continue;
        }
        drmModeConnector *c = find_connector(fd, d->connector, why, sizeof why);
        if (c) {
            p->fd = fd;
            snprintf(p->device, sizeof p->device, "%s", path);
            *conn = c;
        } else {
            close(fd);
            if (used < sizeof tried)
                used += (size_t)snprintf(tried + used, sizeof tried - used, "%s%s: %s",
                                         used ? "; " : "", path, why);
        }
    }
    if (n > 0)
        drmFreeDevices(devs, n);
    if (primaries == 0)
        return swell_fail(err, SWELL_E_UNSUPPORTED, "platform kms: no /dev/dri/card*: no KMS "
                          "display here; use --platform surfaceless");
    if (p->fd < 0)
        return swell_fail(err, SWELL_E_UNSUPPORTED, "platform kms: no connected connector%s%s%s "
                          "with modes on any DRM device (%s); connect a display, name one with "
                          "--connector, or use --platform surfaceless",
                          d->connector ? " named '" : "", d->connector ? d->connector : "",
                          d->connector ? "'" : "", tried);
    return SWELL_OK;
}

/* ---- CRTC, mode, plane --------------------------------------------------------------------- */

int kms_pick_crtc(struct platform *p, const drmModeConnector *c, struct swell_err *err)
{
    drmModeRes *res = drmModeGetResources(p->fd);
    if (!res)
        return swell_fail(err, SWELL_E_DRM, "platform kms: drmModeGetResources on %s: %s",
                          p->device, strerror(errno));
    uint32_t crtc = 0;
    /* Keep the CRTC the connector is already driven by: no other output loses its CRTC. */
    if (c->encoder_id) {
        drmModeEncoder *e = drmModeGetEncoder(p->fd, c->encoder_id);
        if (e) {
            crtc = e->crtc_id;
            drmModeFreeEncoder(e);
        }
    }
    for (int i = 0; i < c->count_encoders && !crtc; i++) {
        drmModeEncoder *e = drmModeGetEncoder(p->fd, c->encoders[i]);
        if (!e)
            continue;
        for (int j = 0; j < res->count_crtcs && !crtc; j++)
            if (e->possible_crtcs & (1u << j))
                crtc = res->crtcs[j];
        drmModeFreeEncoder(e);
    }
    p->crtc_index = -1;
    for (int j = 0; j < res->count_crtcs; j++)
        if (res->crtcs[j] == crtc)
            p->crtc_index = j;
    drmModeFreeResources(res);
    if (!crtc || p->crtc_index < 0)
        return swell_fail(err, SWELL_E_DRM, "platform kms: no CRTC can drive connector %u on %s "
                          "(all in use?)", c->connector_id, p->device);
    p->crtc_id = crtc;
    return SWELL_OK;
}

int kms_mode_hz(const drmModeModeInfo *m)
{
    if (m->vrefresh)
        return (int)m->vrefresh;
    if (!m->htotal || !m->vtotal)
        return 0;
    return (int)((m->clock * 1000.0) / ((double)m->htotal * m->vtotal) + 0.5);
}

/* Preferred mode by default; else exact WxH (@Hz when given, else the highest refresh), else the
 * mode nearest in size (sum of |dw| + |dh|, ties to the preferred/earlier one). */
int kms_pick_mode(struct platform *p, const drmModeConnector *c, const struct platform_desc *d,
                  struct swell_err *err)
{
    if (c->count_modes <= 0)
        return swell_fail(err, SWELL_E_DRM, "platform kms: connector %u reports no modes",
                          c->connector_id);
    int best = -1;
    if (d->mode_w <= 0 || d->mode_h <= 0) {
        for (int i = 0; i < c->count_modes && best < 0; i++)
            if (c->modes[i].type & DRM_MODE_TYPE_PREFERRED)
                best = i;
        if (best < 0)
            best = 0;
    } else {
        for (int i = 0; i < c->count_modes; i++) {
            const drmModeModeInfo *m = &c->modes[i];
            if (m->hdisplay != d->mode_w || m->vdisplay != d->mode_h)
                continue;
            if (d->mode_hz > 0 && kms_mode_hz(m) != d->mode_hz)
                continue;
            if (best < 0 || kms_mode_hz(m) > kms_mode_hz(&c->modes[best]))
                best = i;
        }
        if (best < 0 && d->mode_hz > 0) {
            char list[700];
            size_t used = 0;
            list[0] = '\0';
            for (int i = 0; i < c->count_modes && used < sizeof list; i++)
                used += (size_t)snprintf(list + used, sizeof list - used, "%s%dx%d@%d",
                                         i ? " " : "", c->modes[i].hdisplay,
                                         c->modes[i].vdisplay, kms_mode_hz(&c->modes[i]));
            return swell_fail(err, SWELL_E_DRM, "platform kms: mode %dx%d@%d is not available "
                              "on %s; available: %s", d->mode_w, d->mode_h, d->mode_hz,
                              p->device, list);
        }
        long best_d = -1;
        for (int i = 0; i < c->count_modes && best < 0; i++) {
            const drmModeModeInfo *m = &c->modes[i];
            long dist = labs((long)m->hdisplay - d->mode_w) + labs((long)m->vdisplay - d->mode_h);
            if (best_d < 0 || dist < best_d)
                best_d = dist;
        }
        for (int i = 0; i < c->count_modes && best < 0 && best_d >= 0; i++) {
            const drmModeModeInfo *m = &c->modes[i];
            if (labs((long)m->hdisplay - d->mode_w) + labs((long)m->vdisplay - d->mode_h) == best_d)
                best = i;
        }
    }
    p->mode = c->modes[best];
    return SWELL_OK;
}

int kms_find_props(int fd, uint32_t obj, uint32_t type, const char *const *names, int count,
                   uint32_t *ids, const char *what, struct swell_err *err)
{
    drmModeObjectProperties *props = drmModeObjectGetProperties(fd, obj, type);
    if (!props)
        return swell_fail(err, SWELL_E_DRM, "platform kms: properties of %s %u: %s", what, obj,
                          strerror(errno));
    for (int k = 0; k < count; k++)
        ids[k] = 0;
    for (uint32_t i = 0; i < props->count_props; i++) {
        drmModePropertyRes *pr = drmModeGetProperty(fd, props->props[i]);
        if (!pr)
            continue;
        for (int k = 0; k < count; k++)
            if (strcmp(pr->name, names[k]) == 0)
                ids[k] = pr->prop_id;
        drmModeFreeProperty(pr);
    }
    drmModeFreeObjectProperties(props);
    for (int k = 0; k < count; k++)
        if (!ids[k])
            return swell_fail(err, SWELL_E_DRM, "platform kms: %s %u has no '%s' property "
                              "(atomic modesetting incomplete); try --kms-api legacy", what, obj,
                              names[k]);
    return SWELL_OK;
}

static uint64_t prop_value(int fd, uint32_t obj, uint32_t type, const char *name, uint64_t none)
{
    drmModeObjectProperties *props = drmModeObjectGetProperties(fd, obj, type);
    uint64_t v = none;
    if (!props)
        return v;
    for (uint32_t i = 0; i < props->count_props; i++) {
        drmModePropertyRes *pr = drmModeGetProperty(fd, props->props[i]);
        if (!pr)
            continue;
        if (strcmp(pr->name, name) == 0)
            v = props->prop_values[i];
        drmModeFreeProperty(pr);
    }
    drmModeFreeObjectProperties(props);
    return v;
}

/* The primary plane that can sit on our CRTC (atomic needs it named explicitly). */
int kms_pick_plane(struct platform *p, struct swell_err *err)
{
    drmModePlaneRes *pres = drmModeGetPlaneResources(p->fd);
    if (!pres)
        return swell_fail(err, SWELL_E_DRM, "platform kms: drmModeGetPlaneResources: %s",
                          strerror(errno));
    for (uint32_t i = 0; i < pres->count_planes && !p->plane_id; i++) {
        drmModePlane *pl = drmModeGetPlane(p->fd, pres->planes[i]);
        if (!pl)
            continue;
        if ((pl->possible_crtcs & (1u << p->crtc_index)) &&
            prop_value(p->fd, pl->plane_id, DRM_MODE_OBJECT_PLANE, "type", ~0ull) ==
                DRM_PLANE_TYPE_PRIMARY)
            p->plane_id = pl->plane_id;
        drmModeFreePlane(pl);
    }
    drmModeFreePlaneResources(pres);
    if (!p->plane_id)
        return swell_fail(err, SWELL_E_DRM, "platform kms: no primary plane for CRTC %u on %s; "
                          "try --kms-api legacy", p->crtc_id, p->device);
    return SWELL_OK;
}
