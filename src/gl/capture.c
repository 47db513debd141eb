/* capture.c - stderr over a span of calls (capture.h). */
#include "gl/capture.h"

#include <string.h>
#include <unistd.h>

void capture_begin(struct capture *c)
{
    c->saved = -1;
    c->file = NULL;
    fflush(stderr);
    FILE *f = tmpfile();
    if (!f)
        return;
    int saved = dup(2);
    if (saved < 0 || dup2(fileno(f), 2) < 0) {
        if (saved >= 0)
            close(saved);
        fclose(f);
        return;
    }
    c->saved = saved;
    c->file = f;
}

void capture_end(struct capture *c, char *text, size_t size)
{
    size_t n = 0;
    if (size)
        text[0] = '\0';
    if (c->saved < 0)
        return;
    fflush(stderr);
    dup2(c->saved, 2);
    close(c->saved);
    c->saved = -1;
    rewind(c->file);
    char buf[4096];
    size_t got;
    while ((got = fread(buf, 1, sizeof buf, c->file)) > 0) {
        fwrite(buf, 1, got, stderr);
        size_t room = size > n + 1 ? size - n - 1 : 0;
        size_t keep = got < room ? got : room;
        memcpy(text + n, buf, keep);
        n += keep;
    }
    if (size)
        text[n] = '\0';
    fclose(c->file);
    c->file = NULL;
}

/* What the drivers swell targets print when they cannot run a shader they compiled and linked:
 * etnaviv past its instruction or register limits, vc4 out of registers, lima's vertex
 * processor past 512 instructions, and their compile failures. */
static const char *const refusal_text[] = {
    "not okay", "Failed to register allocate", "compile failed", "failed to compile",
    "Failed to compile", "exceeds maximum", "exceeds limit", "fail schedule", "gpir: fail",
    "ppir: fail",
};

int capture_refused(const char *text)
{
    for (size_t i = 0; i < sizeof refusal_text / sizeof refusal_text[0]; i++)
        if (strstr(text, refusal_text[i]))
            return 1;
    return 0;
}
