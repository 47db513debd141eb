/* glstate.c - save and restore what an embedded draw changes (glstate.h). */
#include <GLES3/gl3.h>
#include <string.h>
#include "gl/glstate.h"

/* The current context is GLES 3 or later ("OpenGL ES 3.2 Mesa ..."). */
static int context_es3(void)
{
    const char *v = (const char *)glGetString(GL_VERSION);
    const char *p = v ? strstr(v, "OpenGL ES ") : NULL;
    return p && p[10] >= '3' && p[10] <= '9';
}

void gl_state_save(struct gl_state *s, int unit0, int units)
{
    int es3 = context_es3();
    s->es3 = es3;
    if (es3) {
        glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &s->vertex_array);
        glBindVertexArray(0);         /* swell's attributes must not land in the app's VAO */
    }
    glGetIntegerv(GL_CURRENT_PROGRAM, &s->program);
    glGetIntegerv(GL_ARRAY_BUFFER_BINDING, &s->array_buffer);
    glGetIntegerv(GL_ELEMENT_ARRAY_BUFFER_BINDING, &s->element_buffer);
    glGetIntegerv(GL_FRAMEBUFFER_BINDING, &s->framebuffer);
    glGetIntegerv(GL_ACTIVE_TEXTURE, &s->active_texture);
    /* never past the device's units (Mali-450 and GC2000 have 8 or 16: glActiveTexture beyond
     * them is GL_INVALID_ENUM, and the error would be the application's next check's) */
    GLint max_units = 0;
    glGetIntegerv(GL_MAX_COMBINED_TEXTURE_IMAGE_UNITS, &max_units);
    s->unit0 = unit0;
    s->units = units < GL_STATE_UNITS ? units : GL_STATE_UNITS;
    if (s->units > max_units - unit0)
        s->units = max_units - unit0 > 0 ? max_units - unit0 : 0;
    for (int u = 0; u < s->units; u++) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)(unit0 + u));
        glGetIntegerv(GL_TEXTURE_BINDING_2D, &s->texture[u]);
    }
    glActiveTexture((GLenum)s->active_texture);
    for (GLuint a = 0; a < GL_STATE_ATTRIBS; a++) {
        struct gl_attrib_state *v = &s->attrib[a];
        glGetVertexAttribiv(a, GL_VERTEX_ATTRIB_ARRAY_ENABLED, &v->enabled);
        glGetVertexAttribiv(a, GL_VERTEX_ATTRIB_ARRAY_SIZE, &v->size);
        glGetVertexAttribiv(a, GL_VERTEX_ATTRIB_ARRAY_TYPE, &v->type);
        glGetVertexAttribiv(a, GL_VERTEX_ATTRIB_ARRAY_NORMALIZED, &v->normalized);
        glGetVertexAttribiv(a, GL_VERTEX_ATTRIB_ARRAY_STRIDE, &v->stride);
        glGetVertexAttribiv(a, GL_VERTEX_ATTRIB_ARRAY_BUFFER_BINDING, &v->buffer);
        glGetVertexAttribPointerv(a, GL_VERTEX_ATTRIB_ARRAY_POINTER, &v->pointer);
    }
    s->blend = glIsEnabled(GL_BLEND);
    s->depth_test = glIsEnabled(GL_DEPTH_TEST);
    s->cull_face = glIsEnabled(GL_CULL_FACE);
    s->scissor_test = glIsEnabled(GL_SCISSOR_TEST);
    glGetBooleanv(GL_DEPTH_WRITEMASK, &s->depth_mask);
    glGetIntegerv(GL_BLEND_SRC_RGB, &s->blend_src_rgb);
    glGetIntegerv(GL_BLEND_DST_RGB, &s->blend_dst_rgb);
    glGetIntegerv(GL_BLEND_SRC_ALPHA, &s->blend_src_alpha);
    glGetIntegerv(GL_BLEND_DST_ALPHA, &s->blend_dst_alpha);
    glGetFloatv(GL_BLEND_COLOR, s->blend_color);
    glGetFloatv(GL_COLOR_CLEAR_VALUE, s->clear_color);
    glGetIntegerv(GL_DEPTH_FUNC, &s->depth_func);
    glGetIntegerv(GL_VIEWPORT, s->viewport);
    glGetIntegerv(GL_SCISSOR_BOX, s->scissor_box);
    glGetIntegerv(GL_UNPACK_ALIGNMENT, &s->unpack_alignment);
}

static void enable(GLenum cap, GLboolean on)
{
    if (on)
        glEnable(cap);
    else
        glDisable(cap);
}

void gl_state_restore(const struct gl_state *s)
{
    for (GLuint a = 0; a < GL_STATE_ATTRIBS; a++) {
        const struct gl_attrib_state *v = &s->attrib[a];
        glBindBuffer(GL_ARRAY_BUFFER, (GLuint)v->buffer);
        if (v->buffer || v->pointer)
            glVertexAttribPointer(a, v->size, (GLenum)v->type, (GLboolean)v->normalized,
                                  v->stride, v->pointer);
        if (v->enabled)
            glEnableVertexAttribArray(a);
        else
            glDisableVertexAttribArray(a);
    }
    for (int u = 0; u < s->units; u++) {
        glActiveTexture(GL_TEXTURE0 + (GLenum)(s->unit0 + u));
        glBindTexture(GL_TEXTURE_2D, (GLuint)s->texture[u]);
    }
    glActiveTexture((GLenum)s->active_texture);
    glUseProgram((GLuint)s->program);
    glBindBuffer(GL_ARRAY_BUFFER, (GLuint)s->array_buffer);
    glBindFramebuffer(GL_FRAMEBUFFER, (GLuint)s->framebuffer);
    enable(GL_BLEND, s->blend);
    enable(GL_DEPTH_TEST, s->depth_test);
    enable(GL_CULL_FACE, s->cull_face);
    enable(GL_SCISSOR_TEST, s->scissor_test);
    glDepthMask(s->depth_mask);
    glBlendFuncSeparate((GLenum)s->blend_src_rgb, (GLenum)s->blend_dst_rgb,
                        (GLenum)s->blend_src_alpha, (GLenum)s->blend_dst_alpha);
    glBlendColor(s->blend_color[0], s->blend_color[1], s->blend_color[2], s->blend_color[3]);
    glClearColor(s->clear_color[0], s->clear_color[1], s->clear_color[2], s->clear_color[3]);
    glDepthFunc((GLenum)s->depth_func);
    glViewport(s->viewport[0], s->viewport[1], s->viewport[2], s->viewport[3]);
    glScissor(s->scissor_box[0], s->scissor_box[1], s->scissor_box[2], s->scissor_box[3]);
    glPixelStorei(GL_UNPACK_ALIGNMENT, s->unpack_alignment);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, (GLuint)s->element_buffer);   /* vertex array 0's */
    if (s->es3)
        glBindVertexArray((GLuint)s->vertex_array);
}
