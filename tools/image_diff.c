/* image_diff.c - two PNGs compared with core/image.h image_compare, for tests in shell:
 *
 *   image-diff A.png B.png MAX RMSE     exit 0 when the largest channel difference is at most
 *                                       MAX (0..255) and the RMSE at most RMSE; prints both
 *
 * make test-cross compares a frame rendered by the arm64 build (under qemu-user) with this
 * machine's. */
#include <stdio.h>
#include <stdlib.h>
#include "core/image.h"

int main(int argc, char **argv)
{
    if (argc != 5) {
        fprintf(stderr, "usage: image-diff A.png B.png MAX RMSE\n");
        return 2;
    }
    struct swell_err err;
    uint8_t *a = NULL, *b = NULL;
    int wa, ha, wb, hb;
    if (image_read_png(argv[1], &a, &wa, &ha, &err) || image_read_png(argv[2], &b, &wb, &hb, &err)) {
        fprintf(stderr, "image-diff: %s\n", err.msg);
        free(a);
        return 2;
    }
    int rc = 1;
    if (wa != wb || ha != hb) {
        printf("image-diff: %dx%d against %dx%d\n", wa, ha, wb, hb);
    } else {
        struct image_diff d;
        int max = atoi(argv[3]);
        image_compare(a, b, wa, ha, max, &d);
        printf("image-diff: %dx%d, largest difference %d/255 (at most %d), RMSE %.3f (at most "
               "%s), %ld pixels over\n", wa, ha, d.max_abs, max, d.rmse, argv[4], d.pixels_over);
        rc = d.max_abs <= max && d.rmse <= atof(argv[4]) ? 0 : 1;
    }
    free(a);
    free(b);
    return rc;
}
