/* vshade.h - the vertex stage's shading on the CPU, for gles2-min where the driver refuses the
 * vertex shaders that evaluate it (issue 15; renderer.c renderer_create tries this build).
 *
 * On gles2-min the CPU already displaces every vertex (grid.c); the terms ocean.vert derives
 * from a vertex's position alone (shaders_gles/vterms.glsl vertex_terms) are computed here as
 * well, once per frame, so the GPU's vertex shader only reads them: the two lookups of Hu
 * §5.1's Fresnel texture and Bruneton §5.2's sky map linearised in the fine-scale slope (their
 * value at the vertex's mean slope s0 and forward differences over the step h), the slowly
 * varying factors of Bruneton eq. 15's Ross BRDF, eq. 27's sky footprint, the aerial
 * perspective (sky.h sky_haze) and the pixel footprint (renderer.c row_footprint).
 * test_glsl's test_vshade compares the two.
 *
 * Why: Vivante GC2000's vertex shaders are limited to 256 instructions and these terms take
 * 200-250 of them (three lookups, each a normalisation, an asin, a square root and a
 * stereographic division). The price is CPU time: about 1,200 instructions a vertex, 5.3 M a
 * frame for the projected grid's 4,480 vertices (callgrind), which is why the vertex shader
 * keeps them wherever the driver takes it.
 *
 * Everything is camera-relative (camera.h), as grid.c's output. */
#ifndef SWELL_VSHADE_H
#define SWELL_VSHADE_H

/* Vertex layout of the buffer the gles2-min programs read, floats (eight vec4 attributes at
 * most, GLES 2's minimum):
 *   pos   displaced position xyz, m; w: log2 of the pixel footprint at the rest point, m
 *   rest  rest position on the sea plane xy, m; the CPU patterns' resolved slope variance xy
 *   geo   the CPU patterns' foam memory mean and variance (Dupuy eq. 7-8); the sky map's eq. 27
 *         LOD offset log2(2 h size / (1 + r_z)); the haze's green transmittance
 *   lin   Fresnel-texture uv and sky-map uv at s0; lin_dx, lin_dy: their derivatives in s
 *   sun   zeta_h - s0 (xy), the Ross factor, eq. 25's x weight
 *   fog   low quality: the in-scattered light of the path to the camera, rgb; high: the
 *         haze's Rayleigh and Mie phase weights at the view's azimuth, 0; w: the grid's
 *         GRID_A_PAD (the wave mask's amplitude, grid_set_mask) */
enum vshade_attr {
    VSHADE_POS = 0, VSHADE_REST = 4, VSHADE_GEO = 8, VSHADE_LIN = 12, VSHADE_LIN_DX = 16,
    VSHADE_LIN_DY = 20, VSHADE_SUN = 24, VSHADE_FOG = 28, VSHADE_FLOATS = 32
};

/* Per frame: the values ocean.vert takes as uniforms for the same terms (renderer.c fills
 * both from one place). */
struct vshade_frame {
    float lin_s0[3];            /* every slot's mean slope xy; the step h (renderer.c) */
    float total_var[2];         /* every pattern's slope variance + the unresolved */
    float sun_dir[3];           /* towards the sun, world */
    float fresnel_uv_scale[2];  /* the Fresnel texels' share of the atlas */
    float sky_map_size;         /* texels */
    float lod_frame[2];         /* altitude^2, log2(pixel angle / altitude) */
    float haze_tau[3];          /* vertical optical depth per channel */
    float haze_frame[2];        /* air mass per metre of path; Mie g */
    float haze_ray[3];          /* horizon Rayleigh and Mie radiances (x exposure) */
    float haze_mie[3];
    int fog;                    /* 1: fill fog (low quality), 0: the phase weights (high) */
};

/* The input vertex layout is grid.h's (GRID_FLOATS per vertex); out holds n * VSHADE_FLOATS. */
void vshade_fill(const struct vshade_frame *f, const float *grid_verts, int n, float *out);

#endif
