/* fsutil.h - the file-system operations the table files need: atomic replace, mkdir -p and a
 * bounded whole-file read (STYLE.md 10: data files are written atomically).
 */
#ifndef SWELL_FSUTIL_H
#define SWELL_FSUTIL_H

#include <stddef.h>
#include <stdint.h>
#include <sys/types.h>
#include "core/err.h"

/* Suffix marker of the temporary files fs_write_atomic creates ("<path>.tmp.XXXXXX"). A reader
 * never opens such a file; a killed writer leaves one behind and nothing else changes. */
#define FS_TEMP_MARKER ".tmp."

/* Create `path` and its missing parents (mode 0777 & ~umask). Existing directories are fine. */
int fs_mkdir_p(const char *path, struct swell_err *err);

/* Replace `path` with `len` bytes so that a reader sees the old file or the new one, never a
 * mix: temp file in the same directory, write, fsync, rename over `path`, fsync the directory.
 * On failure the temp file is removed and `path` is untouched. */
int fs_write_atomic(const char *path, const void *data, size_t len, struct swell_err *err);

/* Remove `path` (missing is fine) and fsync its directory so the removal is durable. */
int fs_remove_durable(const char *path, struct swell_err *err);
/* fsync the directory holding path ("." when none), so a rename or unlink in it is durable;
 * a file system that cannot sync a directory (EINVAL) is not an error. */
int fs_sync_parent(const char *path, struct swell_err *err);
/* The process's umask, read without changing it. */
mode_t fs_umask(void);

/* Read the whole regular file into a malloc'd buffer with one extra NUL byte after the data
 * (so text can be scanned safely). Files larger than max_bytes are refused before reading. */
int fs_read_file(const char *path, size_t max_bytes, uint8_t **out, size_t *out_len,
                 struct swell_err *err);

/* "dir/name" into buf; SWELL_E_ARG when it does not fit. */
int fs_join(char *buf, size_t cap, const char *dir, const char *name, struct swell_err *err);

/* A growable byte buffer (PNG encoding, shader assembly): every append keeps a NUL after the
 * data; when an allocation fails `oom` is set and later appends do nothing, so callers check
 * once at the end. Free `p` when done. */
struct membuf {
    char *p;
    size_t n, cap;
    int oom;
};
void membuf_add(struct membuf *b, const void *data, size_t n);

/* zlib CRC-32 of n bytes (any length: zlib takes uInt, so large buffers go in pieces). */
uint32_t fs_crc32(const void *data, size_t n);
/* Continue a crc32: fs_crc32_more(fs_crc32(a, n), b, m) is the crc32 of a then b. */
uint32_t fs_crc32_more(uint32_t crc, const void *data, size_t n);

#endif
