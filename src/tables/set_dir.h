/* set_dir.h - the folder a table set is published to: a bake owns only what it writes
 * (issue 17 item 3; before, baking into a folder deleted every *.ktx file in it that the new
 * set did not list, symlinks included, and two bakes into one folder could leave it unloadable).
 *
 *  - The set is written into a new folder "<dir>.tmp.XXXXXX" beside dir and swapped in at once
 *    (renameat2 RENAME_EXCHANGE): a reader finds the old set or the new one, never a mix or
 *    none. Where the file system cannot exchange (EINVAL: vfat, some network file systems),
 *    dir is first renamed aside; for that moment a reader finds no set, still never a mix.
 *  - An existing dir is replaced only when it holds nothing but a table set: manifest.swell,
 *    regular files named as tables (tables_layout's names + ".ktx") and swell's temporary files.
 *    Anything else (another file, a symlink, a folder) is refused before anything is written.
 *    dir may be a symlink to a folder: the folder it points to is replaced, the link kept.
 *  - Bakes swapping into one parent folder take turns (flock on the parent, held only for the
 *    check and the swap, milliseconds), so concurrent bakes into one dir both finish and dir
 *    holds one complete set, the last one's.
 *  - "<dir>.tmp.*" folders left by killed bakes are removed by the next bake into dir when no
 *    process holds them (each bake holds a flock on its own while it writes) and they hold only
 *    a set's files.
 */
#ifndef SWELL_SET_DIR_H
#define SWELL_SET_DIR_H

#include "core/err.h"

#define SET_DIR_PATH_MAX 4096

struct set_dir {
    char target[SET_DIR_PATH_MAX];  /* dir resolved (a symlink followed) */
    char tmp[SET_DIR_PATH_MAX];     /* where the new set is written */
    int tmp_fd;                     /* holds the flock on tmp while it is written */
};

/* Check that dir may be replaced, create its parents and the temporary folder. On failure
 * nothing was created but dir's missing parents. */
int set_dir_begin(struct set_dir *p, const char *dir, struct swell_err *err);

/* Swap the temporary folder in as dir and remove the set it replaces; fsyncs the parent. On
 * failure dir is as it was and the temporary folder is removed. */
int set_dir_commit(struct set_dir *p, struct swell_err *err);

/* Remove the temporary folder and what was written into it. */
void set_dir_abort(struct set_dir *p);

#endif
