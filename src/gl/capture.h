/* capture.h - what this process writes to stderr over a span of calls, kept and passed on.
 *
 * The GPU drivers swell runs on report a shader they cannot run only on stderr (etnaviv's
 * "compiled shaders are not okay", vc4's "Failed to register allocate"; neither raises a GL
 * error or a KHR_debug message), and only when the program first draws: the renderer's probe
 * (renderer.c) captures each probe draw's output, scans it, and writes it on unchanged. */
#ifndef SWELL_CAPTURE_H
#define SWELL_CAPTURE_H

#include <stddef.h>
#include <stdio.h>

struct capture {
    int saved;      /* the real stderr, dup()ed; -1: not capturing */
    FILE *file;     /* where fd 2 points meanwhile */
};

/* Start capturing fd 2; on any failure nothing is captured (capture_end then gives ""). */
void capture_begin(struct capture *c);
/* Stop: restore fd 2, write what was captured to it, and keep its first size - 1 bytes in
 * text (NUL-terminated). */
void capture_end(struct capture *c, char *text, size_t size);
/* 1 if captured text holds a driver's word that it cannot run a program it built. */
int capture_refused(const char *text);

#endif
