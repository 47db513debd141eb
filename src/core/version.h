/* version.h - swell's version, once: the programs' --version, the bake report's generator,
 * and (read by the Makefile) the shared library's soname and swell.pc. Semantic versioning:
 * MAJOR changes break the API or the table format. */
#ifndef SWELL_VERSION_H
#define SWELL_VERSION_H

#define SWELL_VERSION_MAJOR 0
#define SWELL_VERSION_MINOR 1
#define SWELL_VERSION_PATCH 0
#define SWELL_VERSION "0.1.0"

#endif
