/* args.c - the command line walk (args.h). */
#include <stdio.h>
#include <string.h>
#include "core/args.h"

static int listed(const char *const *list, const char *name)
{
    for (int i = 0; list && list[i]; i++)
        if (!strcmp(list[i], name))
            return 1;
    return 0;
}

int args_next(struct args *a, const char **name, const char **value)
{
    *name = *value = NULL;
    if (a->i >= a->argc)
        return ARGS_END;
    const char *arg = a->argv[a->i++];
    if (!strcmp(arg, "--help") || !strcmp(arg, "-h")) {
        a->usage(stdout);
        return ARGS_DONE;
    }
    if (!strcmp(arg, "--version")) {
        printf("%s\n", a->version);
        return ARGS_DONE;
    }
    if (strncmp(arg, "--", 2) != 0) {
        fprintf(stderr, "%s: unexpected argument '%s' (see --help)\n", a->prog, arg);
        return ARGS_ERROR;
    }
    *name = arg;
    if (listed(a->flags, arg))
        return ARGS_OPTION;
    if (!listed(a->valued, arg) && !(a->valued_too && a->valued_too(arg))) {
        fprintf(stderr, "%s: unknown option '%s' (see --help)\n", a->prog, arg);
        return ARGS_ERROR;
    }
    if (a->i >= a->argc) {
        fprintf(stderr, "%s: %s needs a value (see --help)\n", a->prog, arg);
        return ARGS_ERROR;
    }
    *value = a->argv[a->i++];
    return ARGS_OPTION;
}
