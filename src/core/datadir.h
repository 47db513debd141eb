/* datadir.h - where swell's read-only data is found, from any working directory: the shaders
 * (shaders_gles/) and the presets (tables/), laid out the same in the source tree and in the
 * install directory $(PREFIX)/share/swell (Makefile install).
 *
 * Search order for a subdirectory `sub`, the first that exists wins:
 *   1. $SWELL_DATA_DIR/sub when SWELL_DATA_DIR is set (and only there: an override that names
 *      a directory without `sub` is an error, not a silent fall-back);
 *   2. the source tree the program was built in, when the running program is the uninstalled
 *      build inside it (so a developer's build reads the shaders being edited);
 *   3. share/swell beside the lib/ of the libswell.so this code runs in (an application
 *      linking the installed library), then beside the running program's bin/ (an installed
 *      tree wherever it was put: PREFIX, DESTDIR staging, a moved tree);
 *   4. the install directory the program was built for, $(PREFIX)/share/swell (a program that
 *      links the library from elsewhere);
 *   5. the source tree otherwise (an installed program built from it, while it exists).
 * The working directory is never searched.
 */
#ifndef SWELL_DATADIR_H
#define SWELL_DATADIR_H

#include <stddef.h>
#include <stdio.h>
#include "core/err.h"

#define DATADIR_ENV "SWELL_DATA_DIR"
#define DATADIR_SHADERS "shaders_gles"
#define DATADIR_PRESETS "tables"

/* The directory holding `sub` into out (cap bytes). SWELL_E_IO, naming every place tried and
 * what to do, when none holds it; SWELL_E_ARG when the path does not fit. */
int data_dir_find(const char *sub, char *out, size_t cap, struct swell_err *err);

/* The places data_dir_find tries, in order and without repeats, as directories without `sub`
 * (for messages and --help): fills up to max entries, returns how many. */
#define DATADIR_MAX_CANDIDATES 5
int data_dir_candidates(char (*dirs)[4096], int max);

/* The search order for --help: "Data: ..." lines naming the directories tried, in order. */
void data_dir_usage(FILE *f);

#endif
