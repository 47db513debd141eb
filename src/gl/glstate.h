/* glstate.h - the GL state an embedded draw leaves as it found it (include/swell.h's contract):
 * saved before swell_ocean_draw, restored after. What the renderer changes and this restores:
 * the program, the array and element buffer bindings (and on GLES 3 the vertex array object,
 * unbound while swell draws), the active texture unit and the 2D texture bound on each unit it
 * uses, the vertex attributes 0-7 (enabled, pointer, buffer), blend (enable, functions, colour),
 * depth (test, function, mask), culling, scissor (test, box), the viewport, the clear colour,
 * pixel unpack alignment and the framebuffer binding. Not restored: uniforms of swell's own
 * programs and the contents of swell's own objects.
 */
#ifndef SWELL_GLSTATE_H
#define SWELL_GLSTATE_H

#include <GLES2/gl2.h>

#define GL_STATE_UNITS 32             /* texture units saved, at most */
#define GL_STATE_ATTRIBS 8            /* vertex attributes saved (GLES 2 promises 8) */

struct gl_attrib_state {
    GLint enabled, size, type, normalized, stride, buffer;
    void *pointer;
};

struct gl_state {
    int es3;                          /* GLES 3 context: the vertex array object saved too */
    GLint vertex_array;
    GLint program, array_buffer, element_buffer, framebuffer, active_texture;
    int unit0, units;                 /* the units saved: unit0 .. unit0 + units - 1 */
    GLint texture[GL_STATE_UNITS];
    struct gl_attrib_state attrib[GL_STATE_ATTRIBS];
    GLboolean blend, depth_test, cull_face, scissor_test, depth_mask;
    GLint blend_src_rgb, blend_dst_rgb, blend_src_alpha, blend_dst_alpha;
    GLfloat blend_color[4], clear_color[4];
    GLint depth_func, viewport[4], scissor_box[4], unpack_alignment;
};

/* units: how many texture units to save from unit0 (the renderer's; at most GL_STATE_UNITS).
 * The vertex array object too when the current context is GLES 3 or later. */
void gl_state_save(struct gl_state *s, int unit0, int units);
void gl_state_restore(const struct gl_state *s);

#endif
