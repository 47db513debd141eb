/* ktx.h - one struct swell_table <-> one KTX 1.1 file (Khronos KTX File Format Specification
 * 1.1), written little-endian, with swell's metadata in the key/value block:
 *     swell.version  "2"               (another value: SWELL_E_VERSION; 2 added swell.set)
 *     swell.name     table name        ([a-z0-9_], 1..31 chars)
 *     swell.kind     "slope", ...      (table_kind_name)
 *     swell.pattern  "-1".."3"
 *     swell.scale, swell.bias  four floats "%.9g %.9g %.9g %.9g" (round-trip exact)
 *     swell.crc32    "0x%08x", zlib crc32 of the image data exactly as in table->data
 *     swell.set      "0x%08x", table->set_id: the sea state the set was baked from
 *                    (tables_io.h), so a table of another bake is refused
 *     KTXorientation "S=r,T=u"         (rows bottom-up, as GL uploads them)
 * The reader checks every header field, every size against the buffer length before any
 * allocation, the padding rules, the metadata and the checksum; messages name the file and
 * the field. It is safe on arbitrary input (fuzz target: ktx_read_memory).
 */
#ifndef SWELL_KTX_H
#define SWELL_KTX_H

#include <stddef.h>
#include <stdint.h>
#include "core/err.h"
#include "tables/tables.h"

#define KTX_SWELL_VERSION 2
#define KTX_MAX_DIM       8192
#define KTX_MAX_LAYERS    1024
/* GL enums the files use (GLES2 headers lack GL_HALF_FLOAT; its value is fixed by KTX). */
#define KTX_GL_UNSIGNED_BYTE 0x1401
#define KTX_GL_HALF_FLOAT    0x140B
#define KTX_GL_RGBA          0x1908
#define KTX_GL_RGBA8         0x8058
#define KTX_GL_RGBA16F       0x881A

/* Encode t into a malloc'd buffer. Deterministic: the same table gives the same bytes. */
int ktx_write_memory(const struct swell_table *t, uint8_t **out, size_t *out_len,
                     struct swell_err *err);
/* Decode a KTX file held in memory into *out (out->data malloc'd; free with free() or via
 * tables_destroy). On failure *out is zeroed and owns nothing. name_for_errors labels every
 * message (a file name). */
int ktx_read_memory(const void *buf, size_t len, const char *name_for_errors,
                    struct swell_table *out, struct swell_err *err);

/* File versions: write goes through fs_write_atomic. */
int ktx_write_file(const struct swell_table *t, const char *path, struct swell_err *err);
int ktx_read_file(const char *path, struct swell_table *out, struct swell_err *err);

/* Largest KTX file the reader accepts (bigger files are refused before reading). */
#define KTX_MAX_FILE_BYTES ((size_t)1 << 30)

#endif
