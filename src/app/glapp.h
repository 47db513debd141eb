/* glapp.h - the programs' own GL objects (the demo boat, the benchmark's baseline quad): a
 * GLSL ES 1.00 program from two files of the installed shaders, and GL errors as messages. What
 * an application embedding swell writes for itself: the library's GL is reached through
 * swell.h only. */
#ifndef SWELL_APP_GLAPP_H
#define SWELL_APP_GLAPP_H

#include <GLES2/gl2.h>
#include "swell.h"

/* The tier's name as tools/devices.py reads it in the shader labels ("gles2-min"). */
const char *glapp_tier_name(int swell_tier);

/* Program from shaders_gles/vs_file and fs_file (core/datadir.h's search order), each given
 * "#version 100" and, the fragment stage, "precision mediump float;" first; attribute i bound
 * to attribs[i] (attribs ends in NULL). With SWELL_SHADER_LABELS=1 its build is labelled on
 * stderr as the library's programs are ("swell-program: begin VS + FS [] tier TIER"), tier
 * being the ocean's (swell_ocean_stats). *out 0 on failure, err saying file and driver log. */
int glapp_program(const char *vs_file, const char *fs_file, const char *const *attribs,
                  int swell_tier, GLuint *out, struct swell_err *err);
/* SWELL_OK, or SWELL_E_GL naming what (and the error) when glGetError reports one. */
int glapp_check(const char *what, struct swell_err *err);

#endif
