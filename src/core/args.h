/* args.h - the command line of both programs (swell, swell-bake): "--name" options with or
 * without a value, --help/-h and --version. Every error is printed as "prog: ... (see --help)"
 * for the caller to exit 2: an argument that is not an option, an unknown option, a missing
 * value. The values themselves are checked by core/parse.h and core/seastate.h. Needs nothing
 * else of the library: swell-bake links it beside the public libswell.a.
 */
#ifndef SWELL_ARGS_H
#define SWELL_ARGS_H

#include <stdio.h>

struct args {
    const char *prog;                   /* names the program in messages */
    int argc;
    char **argv;
    int i;                              /* next argument; start at 1 */
    const char *const *flags;           /* options without a value, NULL-terminated */
    const char *const *valued;          /* options with a value, NULL-terminated */
    int (*valued_too)(const char *name);  /* NULL, or 1 for further options that take a value
                                         * (swell-bake: the sea state's, swell_sea_option) */
    void (*usage)(FILE *out);           /* --help's text */
    const char *version;                /* --version's line */
};

enum { ARGS_ERROR = -1, ARGS_END = 0, ARGS_OPTION, ARGS_DONE };

/* The next option: ARGS_OPTION with *name and *value (NULL for a flag); ARGS_DONE after
 * printing --help or --version to stdout (the program exits 0); ARGS_END after the last;
 * ARGS_ERROR with the message printed to stderr (the program exits 2). */
int args_next(struct args *a, const char **name, const char **value);

#endif
