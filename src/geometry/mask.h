/* mask.h - locally varying wave parameters by a coarse mask (issue 18; Bruneton et al. 2010
 * §6: "calmer water in the lee of an island").
 *
 * The mask is a grid of bytes over a world rectangle: the sea's waves times a = byte / 255
 * there (255: the open sea, 0: still water). A scales what the waves are made of, as a smaller
 * spectrum amplitude would: heights, choppy displacements and slopes by a, slope variances by
 * a^2. The whitecaps follow the wind the amplitude stands for: a fully developed sea's
 * significant height goes as U^2 (Pierson & Moskowitz), so a is (U' / U)^2 for a wind U', and
 * the whitecap fraction W ~ U^b of the sea's model (Tessendorf et al. 2023 eq. 14, b = 3.41;
 * Wu 1988, b = 3.75) is W times a^(b / 2) there (bake/whitecap.h whitecap_model_exponent).
 * Not modelled: the
 * shorter peak wavelength a lighter wind would also bring.
 *
 * Beyond the rectangle the sea is open (a = 1); the mask is read bilinearly between its
 * texels' centres, as GL_LINEAR reads a texture holding it with a border of 255 around
 * (render/mask.c), so the CPU (the grid's vertices, swell_sea_sample) and the GPU (the pixels)
 * read one field. */
#ifndef SWELL_MASK_H
#define SWELL_MASK_H

#include <stdint.h>
#include "core/err.h"
#include "swell.h"

#define WAVE_MASK_MAX SWELL_MASK_MAX_TEXELS   /* 254 (with a border: a 256^2 texture) */
#define WAVE_MASK_MAX_SIZE_M 1.0e6  /* its extent along a side */

struct wave_mask {
    const uint8_t *amp;         /* w x h bytes, row 0 at y0, x growing along a row; not owned */
    int w, h;
    double x0, y0;              /* the world corner of texel (0, 0)'s outer edge, m */
    double dx, dy;              /* a texel's size, m */
};

/* Check a mask's fields and fill m (amp is referenced, not copied); what is wrong, precisely,
 * with SWELL_E_ARG. who names the caller in the message. */
int wave_mask_init(struct wave_mask *m, const char *who, const uint8_t *amp, int w, int h,
                   const double origin_m[2], const double size_m[2], struct swell_err *err);
/* The amplitude factor a at world (x, y), 0..1. */
float wave_mask_at(const struct wave_mask *m, double x, double y);
/* The same at texel coordinates (u, v) = ((x - x0) / dx - 1/2, (y - y0) / dy - 1/2): texel
 * (i, j)'s centre at (i, j); 1 wherever no texel read lies in the mask. */
float wave_mask_texel_at(const struct wave_mask *m, float u, float v);

#endif
