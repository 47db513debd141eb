/* manifest_reseal.c - seal an edited manifest again (set_check.h manifest_reseal), for the
 * tests: tests/cli/test_bad_input.sh edits a value of a baked set, reseals it so the seal no
 * longer stops it, and checks that the value check (src/tables/set_check.h) refuses it. It is
 * what an edit by another program would look like; swell never needs it.
 *
 *   manifest-reseal DIR/manifest.swell     rewrites the file in place (atomically)
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "core/fsutil.h"
#include "tables/set_check.h"
#include "tables/tables_io.h"

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: manifest-reseal FILE\n");
        return 2;
    }
    struct swell_err err;
    swell_err_clear(&err);
    uint8_t *buf = NULL;
    size_t len = 0;
    if (fs_read_file(argv[1], TABLES_MANIFEST_MAX_BYTES, &buf, &len, &err) != 0) {
        fprintf(stderr, "manifest-reseal: %s\n", err.msg);
        return 1;
    }
    size_t cap = len + 64;
    char *text = realloc(buf, cap);
    if (!text) {
        free(buf);
        fprintf(stderr, "manifest-reseal: out of memory\n");
        return 1;
    }
    size_t n = manifest_reseal(text, len, cap);
    int rc = n == 0 ? 1 : fs_write_atomic(argv[1], text, n, &err) != 0;
    if (rc)
        fprintf(stderr, "manifest-reseal: %s: %s\n", argv[1],
                n == 0 ? "does not end with a newline" : err.msg);
    free(text);
    return rc;
}
