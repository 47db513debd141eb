#include "tables/set_dir.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include "core/fsutil.h"
#include "tables/tables.h"
#include "tables/tables_io.h"

#define TMP_INFIX ".tmp."

/* A name a table set's folder holds: the manifest, a table file, a temporary file. */
static int is_set_file(const char *name)
{
    if (strcmp(name, TABLES_MANIFEST_NAME) == 0 || strstr(name, FS_TEMP_MARKER))
        return 1;
    struct seastate every = { .patterns = SWELL_MAX_PATTERNS, .size_fs = 16, .size_geo = 16,
                              .frames = 4 };
    struct swell_table names[SWELL_MAX_TABLES];
    int n = tables_layout(&every, names);
    for (int i = 0; i < n; i++) {
        size_t len = strlen(names[i].name);
        if (strncmp(name, names[i].name, len) == 0 && strcmp(name + len, ".ktx") == 0)
            return 1;
    }
    return 0;
}

/* a + b into out (SET_DIR_PATH_MAX); -1 when it does not fit. */
static int cat2(char *out, const char *a, const char *b)
{
    int n = snprintf(out, SET_DIR_PATH_MAX, "%s%s", a, b);
    return n < 0 || n >= SET_DIR_PATH_MAX ? -1 : 0;
}

/* SWELL_OK when dir holds nothing but regular files of a table set. */
static int check_owned(const char *dir, struct swell_err *err)
{
    DIR *d = opendir(dir);
    if (!d)
        return swell_fail(err, SWELL_E_IO, "cannot list '%s': %s", dir, strerror(errno));
    int rc = 0;
    struct dirent *e;
    while (rc == 0 && (e = readdir(d)) != NULL) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0)
            continue;
        struct stat st;
        int regular = fstatat(dirfd(d), e->d_name, &st, AT_SYMLINK_NOFOLLOW) == 0 &&
                      S_ISREG(st.st_mode);
        if (!regular || !is_set_file(e->d_name))
            rc = swell_fail(err, SWELL_E_ARG, "'%s' holds '%s', %s: swell-bake replaces a "
                            "folder only when it holds nothing but a table set; bake into a "
                            "new or empty folder, or move that out", dir, e->d_name,
                            regular ? "a file that is not part of a table set"
                                    : "a symlink, folder or special file");
    }
    closedir(d);
    return rc;
}

/* Remove dir and the set files in it (check_owned first); best effort, for cleaning up. */
static void remove_set_dir(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d)
        return;
    struct dirent *e;
    while ((e = readdir(d)) != NULL)
        if (strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0 &&
            is_set_file(e->d_name))
            unlinkat(dirfd(d), e->d_name, 0);
    closedir(d);
    rmdir(dir);
}

/* parent and base name of path (no trailing '/'). */
static int split(const char *path, char *parent, char *base, struct swell_err *err)
{
    size_t n = strlen(path);
    while (n > 1 && path[n - 1] == '/')
        n--;
    if (n == 0 || n >= SET_DIR_PATH_MAX - 32)
        return swell_fail(err, SWELL_E_ARG, "output folder '%s' is empty or too long", path);
    const char *slash = memrchr(path, '/', n);
    size_t b = slash ? (size_t)(slash - path) + 1 : 0;
    snprintf(base, SET_DIR_PATH_MAX, "%.*s", (int)(n - b), path + b);
    if (strcmp(base, ".") == 0 || strcmp(base, "..") == 0 || strcmp(base, "/") == 0)
        return swell_fail(err, SWELL_E_ARG, "output folder '%s': name a folder to create or "
                          "replace, not '.', '..' or '/'", path);
    if (b == 0)
        snprintf(parent, SET_DIR_PATH_MAX, ".");
    else
        snprintf(parent, SET_DIR_PATH_MAX, "%.*s", b > 1 ? (int)(b - 1) : 1, path);
    return 0;
}

/* The flock on path's parent folder (blocking; bakes hold it for milliseconds): its fd, or -1
 * with err set. Closing the fd releases it. */
static int lock_parent(const char *path, struct swell_err *err)
{
    char parent[SET_DIR_PATH_MAX], base[SET_DIR_PATH_MAX];
    if (split(path, parent, base, err) != 0)
        return -1;
    int fd = open(parent, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (fd < 0 || flock(fd, LOCK_EX) != 0) {
        swell_fail(err, SWELL_E_IO, "cannot lock '%s' to publish the set: %s", parent,
                   strerror(errno));
        if (fd >= 0)
            close(fd);
        return -1;
    }
    return fd;
}

int set_dir_begin(struct set_dir *p, const char *dir, struct swell_err *err)
{
    memset(p, 0, sizeof *p);
    p->tmp_fd = -1;
    char parent[SET_DIR_PATH_MAX], base[SET_DIR_PATH_MAX];
    int rc = split(dir, parent, base, err);
    if (rc)
        return rc;
    char path[SET_DIR_PATH_MAX];   /* dir without trailing '/' (split checked its length) */
    size_t n = strlen(dir);
    while (n > 1 && dir[n - 1] == '/')
        n--;
    snprintf(path, sizeof path, "%.*s", (int)n, dir);
    dir = path;
    struct stat st;
    if (lstat(dir, &st) == 0) {
        if (S_ISLNK(st.st_mode) && !realpath(dir, p->target))
            return swell_fail(err, SWELL_E_IO, "'%s' is a symlink to nothing usable: %s", dir,
                              strerror(errno));
        if (!S_ISLNK(st.st_mode) && cat2(p->target, dir, "") != 0)
            return swell_fail(err, SWELL_E_ARG, "output folder '%s' is too long", dir);
        if (stat(p->target, &st) != 0 || !S_ISDIR(st.st_mode))
            return swell_fail(err, SWELL_E_IO, "'%s' exists but is not a directory; remove it "
                              "or choose another output directory", dir);
    } else if (errno == ENOENT) {
        if ((rc = fs_mkdir_p(parent, err)))
            return rc;
        if (cat2(p->target, dir, "") != 0)
            return swell_fail(err, SWELL_E_ARG, "output folder '%s' is too long", dir);
    } else {
        return swell_fail(err, SWELL_E_IO, "cannot look at '%s': %s", dir, strerror(errno));
    }
    /* Under the parent's lock: the check of what dir holds (another bake's swap, under it too,
     * is not half done), and the new folder made and locked, so another bake's clean_stale
     * (under it as well) never finds it unlocked and takes it for a killed bake's. */
    int lock = lock_parent(p->target, err);
    if (lock < 0)
        return err ? err->code : SWELL_E_IO;
    if (lstat(p->target, &st) == 0 && (rc = check_owned(p->target, err)) != 0) {
        close(lock);
        return rc;
    }
    if (cat2(p->tmp, p->target, TMP_INFIX "XXXXXX") != 0 || !mkdtemp(p->tmp)) {
        rc = swell_fail(err, SWELL_E_IO, "cannot create directory '%s': %s; check the "
                        "parent's permissions", p->tmp, strerror(errno));
        p->tmp[0] = '\0';
        close(lock);
        return rc;
    }
    /* mkdtemp makes 0700; the set's folder gets what mkdir(0777) would */
    p->tmp_fd = open(p->tmp, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
    if (chmod(p->tmp, 0777 & ~fs_umask()) != 0 || p->tmp_fd < 0 ||
        flock(p->tmp_fd, LOCK_EX) != 0) {
        rc = swell_fail(err, SWELL_E_IO, "cannot prepare '%s': %s", p->tmp, strerror(errno));
        set_dir_abort(p);
    }
    close(lock);
    return rc;
}

/* Folders "<base>.tmp.*" beside target that no bake holds and that hold only set files:
 * left by killed bakes. */
static void clean_stale(const char *parent, const char *base)
{
    DIR *d = opendir(parent);
    if (!d)
        return;
    size_t n = strlen(base);
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        if (strncmp(e->d_name, base, n) != 0 || strncmp(e->d_name + n, TMP_INFIX, 5) != 0)
            continue;
        char path[SET_DIR_PATH_MAX];
        struct stat st;
        if (snprintf(path, sizeof path, "%s/%s", parent, e->d_name) >= (int)sizeof path ||
            lstat(path, &st) != 0 || !S_ISDIR(st.st_mode))
            continue;
        int fd = open(path, O_RDONLY | O_DIRECTORY | O_CLOEXEC);
        if (fd >= 0 && flock(fd, LOCK_EX | LOCK_NB) == 0 && check_owned(path, NULL) == 0)
            remove_set_dir(path);
        if (fd >= 0)
            close(fd);
    }
    closedir(d);
}

/* target -> aside, tmp -> target: for file systems without RENAME_EXCHANGE. */
static int swap_by_two_renames(struct set_dir *p, struct swell_err *err)
{
    char aside[SET_DIR_PATH_MAX];
    if (cat2(aside, p->target, TMP_INFIX "XXXXXX") != 0 || !mkdtemp(aside))
        return swell_fail(err, SWELL_E_IO, "cannot create '%s': %s", aside, strerror(errno));
    if (rename(p->target, aside) != 0) {   /* replaces the empty aside folder */
        int e = errno;
        rmdir(aside);
        return swell_fail(err, SWELL_E_IO, "cannot move '%s' aside: %s", p->target,
                          strerror(e));
    }
    if (rename(p->tmp, p->target) != 0) {
        int e = errno;
        rename(aside, p->target);
        return swell_fail(err, SWELL_E_IO, "cannot rename '%s' to '%s': %s", p->tmp,
                          p->target, strerror(e));
    }
    remove_set_dir(aside);
    return 0;
}

int set_dir_commit(struct set_dir *p, struct swell_err *err)
{
    char parent[SET_DIR_PATH_MAX], base[SET_DIR_PATH_MAX];
    int rc = split(p->target, parent, base, err);
    int lock = rc ? -1 : lock_parent(p->target, err);
    if (rc == 0 && lock < 0)
        rc = err ? err->code : SWELL_E_IO;
    if (rc == 0) {
        clean_stale(parent, base);
        struct stat st;
        if (lstat(p->target, &st) != 0) {
            if (rename(p->tmp, p->target) != 0)
                rc = swell_fail(err, SWELL_E_IO, "cannot rename '%s' to '%s': %s", p->tmp,
                                p->target, strerror(errno));
        } else if ((rc = check_owned(p->target, err)) == 0) {
            if (renameat2(AT_FDCWD, p->tmp, AT_FDCWD, p->target, RENAME_EXCHANGE) == 0)
                remove_set_dir(p->tmp);   /* now the set it replaced */
            else if (errno == EINVAL || errno == ENOSYS)
                rc = swap_by_two_renames(p, err);
            else
                rc = swell_fail(err, SWELL_E_IO, "cannot swap '%s' in as '%s': %s (a mount "
                                "point? bake into a folder inside it)", p->tmp, p->target,
                                strerror(errno));
        }
    }
    if (rc == 0)
        rc = fs_sync_parent(p->target, err);
    else
        set_dir_abort(p);
    if (lock >= 0)
        close(lock);   /* releases the flock */
    if (p->tmp_fd >= 0)
        close(p->tmp_fd);
    p->tmp_fd = -1;
    return rc;
}

void set_dir_abort(struct set_dir *p)
{
    if (p->tmp[0])
        remove_set_dir(p->tmp);
    if (p->tmp_fd >= 0)
        close(p->tmp_fd);
    p->tmp_fd = -1;
    p->tmp[0] = '\0';
}
