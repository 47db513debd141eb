#include "core/fsutil.h"

#include <zlib.h>

#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#ifndef PATH_MAX
#define PATH_MAX 4096
#endif

int fs_join(char *buf, size_t cap, const char *dir, const char *name, struct swell_err *err)
{
    int n = snprintf(buf, cap, "%s/%s", dir, name);
    if (n < 0 || (size_t)n >= cap)
        return swell_fail(err, SWELL_E_ARG, "path '%s/%s' is longer than %zu bytes; use a "
                          "shorter directory", dir, name, cap - 1);
    return 0;
}

int fs_mkdir_p(const char *path, struct swell_err *err)
{
    char buf[PATH_MAX];
    size_t n = strlen(path);
    if (n == 0 || n >= sizeof buf)
        return swell_fail(err, SWELL_E_ARG, "directory path '%s' is empty or longer than %d "
                          "bytes", path, PATH_MAX - 1);
    memcpy(buf, path, n + 1);
    /* Walk each '/' so every prefix exists before its child is created. */
    for (size_t i = 1; i <= n; i++) {
        if (buf[i] != '/' && buf[i] != '\0')
            continue;
        char saved = buf[i];
        buf[i] = '\0';
        if (mkdir(buf, 0777) != 0 && errno != EEXIST)
            return swell_fail(err, SWELL_E_IO, "cannot create directory '%s': %s; check the "
                              "parent's permissions", buf, strerror(errno));
        struct stat st;
        if (stat(buf, &st) != 0 || !S_ISDIR(st.st_mode))
            return swell_fail(err, SWELL_E_IO, "'%s' exists but is not a directory; remove it "
                              "or choose another output directory", buf);
        buf[i] = saved;
    }
    return 0;
}

/* The directory part of path ("." when there is none), for the fsync that makes a rename
 * or unlink durable. */
static void dir_of(const char *path, char *buf, size_t cap)
{
    const char *slash = strrchr(path, '/');
    if (!slash) {
        snprintf(buf, cap, ".");
        return;
    }
    size_t n = (size_t)(slash - path);
    if (n == 0)
        n = 1;
    if (n >= cap)
        n = cap - 1;
    memcpy(buf, path, n);
    buf[n] = '\0';
}

int fs_sync_parent(const char *path, struct swell_err *err)
{
    char dir[PATH_MAX];
    dir_of(path, dir, sizeof dir);
    int fd = open(dir, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0)
        return swell_fail(err, SWELL_E_IO, "cannot open directory '%s' to sync it: %s", dir,
                          strerror(errno));
    int rc = fsync(fd);
    int e = errno;
    close(fd);
    /* Some file systems cannot fsync a directory (EINVAL); the rename itself is still atomic. */
    if (rc != 0 && e != EINVAL)
        return swell_fail(err, SWELL_E_IO, "cannot sync directory '%s': %s", dir, strerror(e));
    return 0;
}

/* The process's umask without changing it (umask(2) can only set it): /proc's Umask line,
 * else the umask(2) round trip (not thread-safe, the kernel has said it since 4.7). */
mode_t fs_umask(void)
{
    FILE *f = fopen("/proc/self/status", "re");
    char line[256];
    unsigned m = 0;
    int found = 0;
    while (f && !found && fgets(line, sizeof line, f))
        found = sscanf(line, "Umask: %o", &m) == 1;
    if (f)
        fclose(f);
    if (found)
        return (mode_t)m;
    mode_t old = umask(022);
    umask(old);
    return old;
}

int fs_write_atomic(const char *path, const void *data, size_t len, struct swell_err *err)
{
    char tmp[PATH_MAX];
    int n = snprintf(tmp, sizeof tmp, "%s" FS_TEMP_MARKER "XXXXXX", path);
    if (n < 0 || (size_t)n >= sizeof tmp)
        return swell_fail(err, SWELL_E_ARG, "path '%s' is too long for a temporary file", path);
    int fd = mkostemp(tmp, O_CLOEXEC);
    if (fd < 0)
        return swell_fail(err, SWELL_E_IO, "cannot create temporary file '%s': %s; check that "
                          "the directory exists and is writable", tmp, strerror(errno));
    int rc = 0;
    const uint8_t *p = data;
    size_t left = len;
    while (left > 0) {
        ssize_t w = write(fd, p, left);
        if (w < 0 && errno == EINTR)
            continue;
        if (w <= 0) {
            rc = swell_fail(err, SWELL_E_IO, "cannot write '%s': %s; check free disk space",
                            tmp, w < 0 ? strerror(errno) : "no progress");
            goto fail;
        }
        p += w;
        left -= (size_t)w;
    }
    /* mkstemp makes 0600 files; a file written here gets what open(0666) would: the umask's */
    if (fchmod(fd, 0666 & ~fs_umask()) != 0) {
        rc = swell_fail(err, SWELL_E_IO, "cannot chmod '%s': %s", tmp, strerror(errno));
        goto fail;
    }
    if (fsync(fd) != 0) {
        rc = swell_fail(err, SWELL_E_IO, "cannot sync '%s': %s", tmp, strerror(errno));
        goto fail;
    }
    if (close(fd) != 0) {
        fd = -1;
        rc = swell_fail(err, SWELL_E_IO, "cannot close '%s': %s", tmp, strerror(errno));
        goto fail;
    }
    fd = -1;
    if (rename(tmp, path) != 0) {
        rc = swell_fail(err, SWELL_E_IO, "cannot rename '%s' to '%s': %s", tmp, path,
                        strerror(errno));
        goto fail;
    }
    return fs_sync_parent(path, err);
fail:
    if (fd >= 0)
        close(fd);
    unlink(tmp);
    return rc;
}

int fs_remove_durable(const char *path, struct swell_err *err)
{
    if (unlink(path) != 0) {
        if (errno == ENOENT)
            return 0;
        return swell_fail(err, SWELL_E_IO, "cannot remove '%s': %s", path, strerror(errno));
    }
    return fs_sync_parent(path, err);
}

int fs_read_file(const char *path, size_t max_bytes, uint8_t **out, size_t *out_len,
                 struct swell_err *err)
{
    *out = NULL;
    *out_len = 0;
    uint8_t *buf = NULL;
    int rc = 0;
    /* O_NONBLOCK: a FIFO (or a device) in place of a file must not hang the open; it is
     * refused below, and a regular file's reads do not care (issue 17) */
    int fd = open(path, O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0)
        return swell_fail(err, SWELL_E_IO, "cannot open '%s': %s", path, strerror(errno));
    struct stat st;
    if (fstat(fd, &st) != 0) {
        rc = swell_fail(err, SWELL_E_IO, "cannot stat '%s': %s", path, strerror(errno));
        goto fail;
    }
    if (!S_ISREG(st.st_mode)) {
        rc = swell_fail(err, SWELL_E_IO, "'%s' is not a regular file (a FIFO, device or "
                        "directory): replace it with the file itself", path);
        goto fail;
    }
    if (st.st_size < 0 || (uint64_t)st.st_size > max_bytes) {
        rc = swell_fail(err, SWELL_E_FORMAT, "'%s' is %lld bytes, more than the %zu allowed; "
                        "the file is corrupt or not what it claims to be", path,
                        (long long)st.st_size, max_bytes);
        goto fail;
    }
    size_t size = (size_t)st.st_size;
    buf = malloc(size + 1);
    if (!buf) {
        rc = swell_fail(err, SWELL_E_NOMEM, "cannot allocate %zu bytes to read '%s'", size + 1,
                        path);
        goto fail;
    }
    size_t got = 0;
    while (got < size) {
        ssize_t r = read(fd, buf + got, size - got);
        if (r < 0 && errno == EINTR)
            continue;
        if (r < 0) {
            rc = swell_fail(err, SWELL_E_IO, "cannot read '%s': %s", path, strerror(errno));
            goto fail;
        }
        if (r == 0) {
            rc = swell_fail(err, SWELL_E_IO, "'%s' shrank while being read (%zu of %zu "
                            "bytes)", path, got, size);
            goto fail;
        }
        got += (size_t)r;
    }
    buf[size] = 0;
    close(fd);
    *out = buf;
    *out_len = size;
    return 0;
fail:
    free(buf);
    close(fd);
    return rc;
}

uint32_t fs_crc32(const void *data, size_t n)
{
    return fs_crc32_more(0, data, n);
}

uint32_t fs_crc32_more(uint32_t crc, const void *data, size_t n)
{
    const uint8_t *p = data;
    uLong c = crc;
    while (n > 0) {
        uInt chunk = n > 0x40000000u ? 0x40000000u : (uInt)n;
        c = crc32(c, p, chunk);
        p += chunk;
        n -= chunk;
    }
    return (uint32_t)c;
}

void membuf_add(struct membuf *b, const void *data, size_t n)
{
    if (b->oom)
        return;
    if (b->n + n + 1 > b->cap) {
        size_t cap = b->cap ? b->cap : 4096;
        while (b->n + n + 1 > cap)
            cap *= 2;
        char *p = realloc(b->p, cap);
        if (!p) {
            b->oom = 1;
            return;
        }
        b->p = p;
        b->cap = cap;
    }
    memcpy(b->p + b->n, data, n);
    b->n += n;
    b->p[b->n] = '\0';
}
