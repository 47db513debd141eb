/* detile.c - random offsets blended on a lattice (detile.h). */
#include <math.h>
#include <stddef.h>
#include "geometry/detile.h"
#include "core/parse.h"

/* A fixed table: the same sea on every machine and in every stage. Bytes from a 32-bit
 * xorshift (Marsaglia 2003) of each index and a fixed seed. */
static uint8_t hash_byte(unsigned i)
{
    uint32_t s = 0x9e3779b9u ^ (i * 0x85ebca6bu);
    for (int k = 0; k < 3; k++) {
        s ^= s << 13;
        s ^= s >> 17;
        s ^= s << 5;
    }
    return (uint8_t)(s >> 26);   /* 6 bits: DETILE_OFFSETS^2 = 64 offsets */
}

uint8_t detile_hash(int x, int y)
{
    unsigned ix = (unsigned)x & (DETILE_N - 1), iy = (unsigned)y & (DETILE_N - 1);
    return hash_byte(iy * DETILE_N + ix);
}

void detile_hash_table(uint8_t *out)
{
    for (unsigned i = 0; i < DETILE_N * DETILE_N; i++)
        out[i] = hash_byte(i);
}

void detile_cell_table(uint8_t *out, size_t stride)
{
    for (int y = 0; y < DETILE_N; y++)
        for (int x = 0; x < DETILE_N; x++) {
            uint8_t *p = out + (size_t)y * stride + 4 * (size_t)x;
            p[0] = detile_hash(x, y);
            p[1] = detile_hash(x + 1, y);
            p[2] = detile_hash(x, y + 1);
            p[3] = detile_hash(x + 1, y + 1);
        }
}

void detile_taps_cell(const uint8_t *hash, long hx, long hy, float fx, float fy,
                      struct detile_taps *t)
{
    unsigned m = DETILE_N - 1;
    unsigned x = (unsigned)hx & m, y = (unsigned)hy & m;
    unsigned x1 = (x + 1) & m, y1 = (y + 1) & m, up = fy > fx;
    unsigned mid = up ? y1 * DETILE_N + x : y * DETILE_N + x1;
    uint8_t h[3];
    if (hash) {
        h[0] = hash[y * DETILE_N + x];
        h[1] = hash[mid];
        h[2] = hash[y1 * DETILE_N + x1];
    } else {
        h[0] = hash_byte(y * DETILE_N + x);
        h[1] = hash_byte(mid);
        h[2] = hash_byte(y1 * DETILE_N + x1);
    }
    /* barycentric weights in the triangle (0,0), (1,0) or (0,1), (1,1) */
    float w0 = 1.0f - (fx > fy ? fx : fy), w1 = fabsf(fx - fy), w2 = fx < fy ? fx : fy;
    float n = 1.0f / sqrtf(w0 * w0 + w1 * w1 + w2 * w2);
    t->w[0] = n * w0;
    t->w[1] = n * w1;
    t->w[2] = n * w2;
    for (int j = 0; j < 3; j++) {
        t->du[j] = (float)(h[j] >> 3) * (1.0f / DETILE_OFFSETS);
        t->dv[j] = (float)(h[j] & 7) * (1.0f / DETILE_OFFSETS);
    }
}

void detile_taps(int pattern, double u, double v, struct detile_taps *t)
{
    double qx = u * DETILE_CELLS, qy = v * DETILE_CELLS, fx = floor(qx), fy = floor(qy);
    /* the cell index modulo the hash period, from a value exact in double */
    long cx = (long)fmod(fx, (double)DETILE_N), cy = (long)fmod(fy, (double)DETILE_N);
    detile_taps_cell(NULL, cx + DETILE_SHIFT_X * pattern, cy + DETILE_SHIFT_Y * pattern,
                     (float)(qx - fx), (float)(qy - fy), t);
}

void detile_taps_off(struct detile_taps *t)
{
    *t = (struct detile_taps){ .w = { 1.0f, 0.0f, 0.0f } };
}

static double wrap(double x, double n)
{
    double m = fmod(x, n);
    return m < 0.0 ? m + n : m;
}

void detile_camera_shift(int pattern, double cam_x, double cam_y, double inv_l, float out[3])
{
    double cx = floor(cam_x * inv_l) * DETILE_CELLS, cy = floor(cam_y * inv_l) * DETILE_CELLS;
    out[0] = (float)wrap(cx + (double)DETILE_SHIFT_X * pattern, DETILE_N);
    out[1] = (float)wrap(cy + (double)DETILE_SHIFT_Y * pattern, DETILE_N);
    out[2] = (float)wrap(cx + cy, 3.0);
}

static const char *const detile_names[DETILE_MODE_COUNT] = { "auto", "on", "off" };
const char *detile_mode_name(int m) { return name_of(detile_names, DETILE_MODE_COUNT, m); }
int detile_mode_from_name(const char *name)
{
    return parse_name(detile_names, 0, DETILE_MODE_COUNT, name);
}
