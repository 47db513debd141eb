/* test_fuzz_replay.c - replays every file in tests/fuzz/corpus/<target>/ and
 * tests/fuzz/regressions/<target>/ through the fuzz targets, built with the ordinary compiler
 * (no libFuzzer), so `make test` (and `make test SAN=address,undefined`) guards every seed and
 * every crash ever found.
 *
 * The targets' own contracts (tests/fuzz/fuzz_*.c) abort on violation. Besides, seed names
 * carry an expectation the loader must meet: "ok_*" must be accepted, "bad_*" refused; other
 * names (files libFuzzer adds, regressions) only have to pass the contracts. Each corpus must
 * hold at least one ok_ and one bad_ seed so a lost corpus fails the test rather than passing.
 * Run from the repository root (tools/run-tests.sh does).
 */
#include <dirent.h>
#include <errno.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#define SWELL_FUZZ_NO_ENTRY
#include "fuzz/fuzz_ktx.c"
#include "fuzz/fuzz_manifest.c"
#include "fuzz/fuzz_preset.c"
#include "fuzz/fuzz_set.c"

#define FUZZ_DIR "tests/fuzz"
#define REPLAY_MAX_BYTES (4u << 20)

struct replay_target {
    const char *name;
    int (*one)(const uint8_t *data, size_t size);
};

struct replay_count {
    int files, ok_seeds, bad_seeds;
};

static int name_filter(const struct dirent *d)
{
    return d->d_name[0] != '.';
}

static uint8_t *slurp(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return NULL;
    uint8_t *buf = malloc(REPLAY_MAX_BYTES);
    size_t n = buf ? fread(buf, 1, REPLAY_MAX_BYTES, f) : 0;
    int too_big = buf && n == REPLAY_MAX_BYTES && fgetc(f) != EOF;
    fclose(f);
    if (!buf || too_big) {
        free(buf);
        return NULL;
    }
    *len = n;
    return buf;
}

/* Replay every file of tests/fuzz/<kind>/<target>; a missing directory counts as empty (regressions start empty). */
static void replay_dir(const struct replay_target *t, const char *kind, struct replay_count *c)
{
    char dir[512];
    snprintf(dir, sizeof dir, "%s/%s/%s", FUZZ_DIR, kind, t->name);
    struct dirent **list = NULL;
    int n = scandir(dir, &list, name_filter, alphasort);
    if (n < 0) {
        assert_int_equal(errno, ENOENT);
        return;
    }
    for (int i = 0; i < n; i++) {
        char path[1024];
        snprintf(path, sizeof path, "%s/%s", dir, list[i]->d_name);
        size_t len = 0;
        uint8_t *data = slurp(path, &len);
        if (!data)
            fail_msg("cannot read %s (or larger than %u bytes)", path, REPLAY_MAX_BYTES);
        /* Printed first so a contract abort in the target names its input in the log. */
        printf("replay %s\n", path);
        fflush(stdout);
        int rc = t->one(data, len);
        free(data);
        c->files++;
        if (strncmp(list[i]->d_name, "ok_", 3) == 0) {
            c->ok_seeds++;
            if (rc != 0)
                fail_msg("%s: seed named ok_ was refused (code %d)", path, rc);
        } else if (strncmp(list[i]->d_name, "bad_", 4) == 0) {
            c->bad_seeds++;
            if (rc == 0)
                fail_msg("%s: seed named bad_ was accepted", path);
        }
        free(list[i]);
    }
    free(list);
}

static void replay(const struct replay_target *t)
{
    struct replay_count c = {0, 0, 0};
    replay_dir(t, "corpus", &c);
    replay_dir(t, "regressions", &c);
    printf("%s: %d files replayed (%d ok_ seeds, %d bad_ seeds)\n", t->name, c.files,
           c.ok_seeds, c.bad_seeds);
    assert_true(c.ok_seeds >= 1);
    assert_true(c.bad_seeds >= 1);
}

static void test_replay_ktx(void **state)
{
    (void)state;
    static const struct replay_target t = {"fuzz_ktx", fuzz_ktx_one};
    replay(&t);
}

static void test_replay_manifest(void **state)
{
    (void)state;
    static const struct replay_target t = {"fuzz_manifest", fuzz_manifest_one};
    replay(&t);
}

static void test_replay_preset(void **state)
{
    (void)state;
    static const struct replay_target t = {"fuzz_preset", fuzz_preset_one};
    replay(&t);
}

static void test_replay_set(void **state)
{
    (void)state;
    static const struct replay_target t = {"fuzz_set", fuzz_set_one};
    replay(&t);
    tables_destroy(&set_base);   /* the target's cached bake */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_replay_ktx),
        cmocka_unit_test(test_replay_manifest),
        cmocka_unit_test(test_replay_preset),
        cmocka_unit_test(test_replay_set),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
