/* boat.c - the swell program's demo boat (boat.h): mesh, pose on the sea, draw. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <GLES2/gl2.h>

#include <cglm/cglm.h>

#include "app/boat.h"
#include "app/glapp.h"
#include "core/err.h"

#define BOAT_VERTS_MAX 256
#define FLOATS 9                    /* position, normal, colour */
#define FREEBOARD 1.0f              /* the deck above the waterline, m */
#define KEEL (-0.7f)                /* the keel below it, m */
#define PI_D 3.14159265358979323846

enum { U_MVP, U_ROT, U_SUN, U_ATT, U_COUNT };

struct boat {
    struct boat_desc d;
    struct boat_pose pose;
    GLuint prog;
    GLint u[U_COUNT];
    GLuint vbo;
    int verts;
};

struct mesh {
    float v[BOAT_VERTS_MAX * FLOATS];
    int n;
};

static void add_vertex(struct mesh *m, const float p[3], const float nrm[3], const float c[3])
{
    if (m->n >= BOAT_VERTS_MAX)
        return;
    float *o = m->v + FLOATS * m->n++;
    memcpy(o, p, 3 * sizeof(float));
    memcpy(o + 3, nrm, 3 * sizeof(float));
    memcpy(o + 6, c, 3 * sizeof(float));
}

/* A flat triangle (its face normal at every corner). */
static void add_tri(struct mesh *m, const float a[3], const float b[3], const float c[3],
                    const float col[3])
{
    float e1[3], e2[3], n[3];
    for (int k = 0; k < 3; k++) {
        e1[k] = b[k] - a[k];
        e2[k] = c[k] - a[k];
    }
    n[0] = e1[1] * e2[2] - e1[2] * e2[1];
    n[1] = e1[2] * e2[0] - e1[0] * e2[2];
    n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    float l = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; k++)
        n[k] = l > 0.0f ? n[k] / l : 0.0f;
    add_vertex(m, a, n, col);
    add_vertex(m, b, n, col);
    add_vertex(m, c, n, col);
}

static void add_quad(struct mesh *m, const float a[3], const float b[3], const float c[3],
                     const float d[3], const float col[3])
{
    add_tri(m, a, b, c, col);
    add_tri(m, a, c, d, col);
}

/* A box without its bottom. */
static void add_box(struct mesh *m, float x0, float x1, float y0, float y1, float z0, float z1,
                    const float side[3], const float top[3])
{
    float p[8][3];
    for (int i = 0; i < 8; i++) {
        p[i][0] = i & 1 ? x1 : x0;
        p[i][1] = i & 2 ? y1 : y0;
        p[i][2] = i & 4 ? z1 : z0;
    }
    add_quad(m, p[0], p[1], p[5], p[4], side);
    add_quad(m, p[2], p[3], p[7], p[6], side);
    add_quad(m, p[0], p[2], p[6], p[4], side);
    add_quad(m, p[1], p[3], p[7], p[5], side);
    add_quad(m, p[4], p[5], p[7], p[6], top);
}

/* Hull (a pointed bow, a transom), deck, cabin and mast, in the boat's frame. */
static void build_mesh(struct mesh *m)
{
    static const float hull[3] = { 0.08f, 0.14f, 0.35f }, bottom[3] = { 0.55f, 0.12f, 0.1f };
    static const float deck[3] = { 0.6f, 0.45f, 0.28f }, cabin[3] = { 0.95f, 0.95f, 0.93f };
    static const float roof[3] = { 0.65f, 0.67f, 0.7f }, mast[3] = { 0.8f, 0.8f, 0.78f };
    const float L = (float)BOAT_LENGTH_M, B = (float)BOAT_BEAM_M;
    /* deck and keel outlines, bow first, round to port, the transom, back to starboard */
    float dk[5][3] = { { L / 2, 0, FREEBOARD }, { L / 6, B / 2, FREEBOARD },
                       { -L / 2, 0.4f * B, FREEBOARD }, { -L / 2, -0.4f * B, FREEBOARD },
                       { L / 6, -B / 2, FREEBOARD } };
    float kl[5][3];
    for (int i = 0; i < 5; i++) {
        kl[i][0] = i == 0 ? dk[i][0] - 1.2f : i >= 2 && i <= 3 ? dk[i][0] + 0.4f : dk[i][0];
        kl[i][1] = 0.35f * dk[i][1];
        kl[i][2] = KEEL;
    }
    for (int i = 0; i < 5; i++) {
        int j = (i + 1) % 5;
        /* the side from the deck down to the waterline white, below it the antifouling */
        float wi[3], wj[3];
        for (int k = 0; k < 3; k++) {
            float s = FREEBOARD / (FREEBOARD - KEEL);
            wi[k] = dk[i][k] + s * (kl[i][k] - dk[i][k]);
            wj[k] = dk[j][k] + s * (kl[j][k] - dk[j][k]);
        }
        add_quad(m, dk[i], dk[j], wj, wi, hull);
        add_quad(m, wi, wj, kl[j], kl[i], bottom);
    }
    for (int i = 1; i + 1 < 5; i++) {
        add_tri(m, dk[0], dk[i], dk[i + 1], deck);
        add_tri(m, kl[0], kl[i], kl[i + 1], bottom);
    }
    add_box(m, -2.6f, 0.6f, -0.95f, 0.95f, FREEBOARD, (float)BOAT_HEIGHT_M - 0.6f, cabin, roof);
    add_box(m, 1.2f, 1.35f, -0.07f, 0.07f, FREEBOARD, (float)BOAT_MAST_M, mast, mast);
}

int boat_create(const struct boat_desc *d, int swell_tier, struct boat **out,
                struct swell_err *err)
{
    static const char *const names[U_COUNT] = { "mvp", "model_rot", "sun_dir", "attenuation" };
    static const char *const attribs[] = { "a_pos", "a_normal", "a_color", NULL };
    struct boat *b = calloc(1, sizeof *b);
    if (!b)
        return swell_fail(err, SWELL_E_NOMEM, "boat: no memory");
    b->d = *d;
    int rc = glapp_program("boat.vert", "boat.frag", attribs, swell_tier, &b->prog, err);
    if (rc) {
        free(b);
        return rc;
    }
    for (int i = 0; i < U_COUNT; i++)
        b->u[i] = glGetUniformLocation(b->prog, names[i]);
    static struct mesh m;
    m.n = 0;
    build_mesh(&m);
    b->verts = m.n;
    glGenBuffers(1, &b->vbo);
    glBindBuffer(GL_ARRAY_BUFFER, b->vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(sizeof(float) * FLOATS * (size_t)m.n), m.v,
                 GL_STATIC_DRAW);
    if ((rc = glapp_check("boat: its mesh", err))) {
        boat_destroy(b);
        return rc;
    }
    *out = b;
    return SWELL_OK;
}

int boat_pose_at(struct boat *b, const swell_sea *sea, int detile, double t_s,
                 struct swell_err *err)
{
    double h = b->d.heading_deg * PI_D / 180.0, ch = cos(h), sh = sin(h);
    double run = b->d.speed_mps * (t_s - b->d.t0_s);
    double x = b->d.x0 + run * ch, y = b->d.y0 + run * sh;
    /* bow, stern (0.8 of the length apart), port, starboard at mid-length */
    const double lx = 0.4 * BOAT_LENGTH_M, ly = 0.5 * BOAT_BEAM_M;
    const double pts[4][2] = { { lx, 0 }, { -lx, 0 }, { 0, ly }, { 0, -ly } };
    double xy[8], z[4];
    for (int i = 0; i < 4; i++) {
        xy[2 * i] = x + pts[i][0] * ch - pts[i][1] * sh;
        xy[2 * i + 1] = y + pts[i][0] * sh + pts[i][1] * ch;
    }
    /* the hull does not feel waves shorter than itself */
    swell_sample_desc sd = { .min_wavelength_m = BOAT_LENGTH_M, .no_detile = !detile,
                             .height_only = 1 };
    swell_sample s[4];
    int rc = swell_sea_sample(sea, &sd, xy, 4, t_s, s, err);
    if (rc)
        return swell_err_context(err, "the boat's pose at t = %.3f s", t_s);
    for (int i = 0; i < 4; i++)
        z[i] = s[i].height_m;
    struct boat_pose *p = &b->pose;
    p->pos[0] = x;
    p->pos[1] = y;
    p->pos[2] = 0.25 * (z[0] + z[1] + z[2] + z[3]);
    double pitch = atan2(z[0] - z[1], 2.0 * lx), roll = atan2(z[2] - z[3], 2.0 * ly);
    p->pitch_deg = (float)(pitch * 180.0 / PI_D);
    p->roll_deg = (float)(roll * 180.0 / PI_D);
    /* R = Rz(heading) Ry(-pitch) Rx(roll): columns are the boat's axes in the world */
    double cp = cos(pitch), sp = sin(pitch), cr = cos(roll), sr = sin(roll);
    double fx[3] = { cp, 0.0, sp };                     /* Ry(-pitch) x */
    double fy[3] = { -sp * sr, cr, cp * sr };           /* Ry(-pitch) Rx(roll) y */
    double fz[3] = { -sp * cr, -sr, cp * cr };
    const double *cols[3] = { fx, fy, fz };
    for (int c = 0; c < 3; c++) {
        p->rot[3 * c + 0] = (float)(ch * cols[c][0] - sh * cols[c][1]);
        p->rot[3 * c + 1] = (float)(sh * cols[c][0] + ch * cols[c][1]);
        p->rot[3 * c + 2] = (float)cols[c][2];
    }
    return SWELL_OK;
}

const struct boat_pose *boat_pose(const struct boat *b)
{
    return &b->pose;
}

const struct boat_desc *boat_get_desc(const struct boat *b)
{
    return &b->d;
}

void boat_draw(const struct boat *b, const float view[16], const float proj[16],
               const double eye[3], const float sun_dir[3], float attenuation_per_m)
{
    const struct boat_pose *p = &b->pose;
    mat4 model = GLM_MAT4_IDENTITY_INIT, v, pr, mvp;
    for (int c = 0; c < 3; c++)
        for (int r = 0; r < 3; r++)
            model[c][r] = p->rot[3 * c + r];
    for (int k = 0; k < 3; k++)
        model[3][k] = (float)(p->pos[k] - eye[k]);
    memcpy(v, view, sizeof v);
    memcpy(pr, proj, sizeof pr);
    glm_mat4_mulN((mat4 *[]){ &pr, &v, &model }, 3, mvp);
    glUseProgram(b->prog);
    glUniformMatrix4fv(b->u[U_MVP], 1, GL_FALSE, (const GLfloat *)mvp);
    glUniformMatrix3fv(b->u[U_ROT], 1, GL_FALSE, p->rot);
    glUniform3fv(b->u[U_SUN], 1, sun_dir);
    /* the hull's world height per vertex: the pose's heave plus the rotated model point */
    glUniform2f(b->u[U_ATT], attenuation_per_m, (float)p->pos[2]);
    glBindBuffer(GL_ARRAY_BUFFER, b->vbo);
    for (GLuint a = 0; a < 3; a++) {
        glEnableVertexAttribArray(a);
        glVertexAttribPointer(a, 3, GL_FLOAT, GL_FALSE, FLOATS * sizeof(float),
                              (const void *)(3 * a * sizeof(float)));
    }
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glDrawArrays(GL_TRIANGLES, 0, b->verts);
    for (GLuint a = 0; a < 3; a++)
        glDisableVertexAttribArray(a);
    glDisable(GL_DEPTH_TEST);
}

void boat_destroy(struct boat *b)
{
    if (!b)
        return;
    if (b->vbo)
        glDeleteBuffers(1, &b->vbo);
    if (b->prog)
        glDeleteProgram(b->prog);
    free(b);
}
