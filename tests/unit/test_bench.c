/* test_bench.c - the benchmark's statistics against their definitions (brute force), the JSON
 * result (escaping, null for what was not measured, truncation, atomic file), and the
 * instruction counter either working (counts grow with work) or saying why not. */
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <setjmp.h>
#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app/bench.h"
#include "core/fsutil.h"

static uint32_t lcg(uint32_t *s)
{
    *s = *s * 1664525u + 1013904223u;
    return *s >> 8;
}

/* The nearest-rank percentile by its definition: the smallest sample value v such that at
 * least p n of the samples are <= v. Quadratic, independent of sorting. */
static double brute_percentile(const double *x, int n, double p)
{
    double best = INFINITY;
    for (int i = 0; i < n; i++) {
        int le = 0;
        for (int j = 0; j < n; j++)
            le += x[j] <= x[i];
        if ((double)le >= p * n - 1e-9 && x[i] < best)
            best = x[i];
    }
    return best;
}

/* The median by its definition: a value with as many samples strictly below as above (for
 * even n the mean of the two values that bracket the middle). */
static double brute_median(const double *x, int n)
{
    double lo = NAN, hi = NAN;
    for (int i = 0; i < n; i++) {
        int below = 0, equal = 0;
        for (int j = 0; j < n; j++) {
            below += x[j] < x[i];
            equal += x[j] == x[i];
        }
        /* x[i] occupies ranks below .. below + equal - 1 (0-based) */
        int rlo = (n - 1) / 2, rhi = n / 2;
        if (below <= rlo && rlo < below + equal)
            lo = x[i];
        if (below <= rhi && rhi < below + equal)
            hi = x[i];
    }
    return 0.5 * (lo + hi);
}

static void test_stats_against_definitions(void **state)
{
    (void)state;
    uint32_t seed = 12345;
    static const int sizes[] = { 1, 2, 3, 7, 20, 99, 100, 101, 257 };
    for (size_t s = 0; s < sizeof sizes / sizeof sizes[0]; s++) {
        int n = sizes[s];
        double *x = malloc((size_t)n * sizeof *x), *y = malloc((size_t)n * sizeof *y);
        assert_non_null(x);
        assert_non_null(y);
        double sum = 0, mn = INFINITY, mx = -INFINITY;
        for (int i = 0; i < n; i++) {
            /* coarse values so ties occur, as with millisecond timings */
            x[i] = 10.0 + (double)(lcg(&seed) % 50) * 0.25;
            y[i] = x[i];
            sum += x[i];
            mn = fmin(mn, x[i]);
            mx = fmax(mx, x[i]);
        }
        struct bench_stats st;
        bench_stats_compute(y, n, &st);
        assert_int_equal(st.n, n);
        assert_true(st.median_ms == brute_median(x, n));
        assert_true(st.p95_ms == brute_percentile(x, n, 0.95));
        assert_true(fabs(st.mean_ms - sum / n) < 1e-9);
        assert_true(st.min_ms == mn);
        assert_true(st.max_ms == mx);
        for (int i = 1; i < n; i++)
            assert_true(y[i - 1] <= y[i]);
        static const double ps[] = { 0.01, 0.5, 0.9, 0.99, 1.0 };
        for (size_t k = 0; k < sizeof ps / sizeof ps[0]; k++)
            assert_true(bench_percentile(y, n, ps[k]) == brute_percentile(x, n, ps[k]));
        free(x);
        free(y);
    }
}

static void test_stats_known_values(void **state)
{
    (void)state;
    /* 1..100 ms: median 50.5, p95 the 95th smallest = 95 (nearest rank), mean 50.5 */
    double x[100];
    for (int i = 0; i < 100; i++)
        x[i] = (double)(100 - i);
    struct bench_stats st;
    bench_stats_compute(x, 100, &st);
    assert_true(st.median_ms == 50.5);
    assert_true(st.p95_ms == 95.0);
    assert_true(st.mean_ms == 50.5);
    assert_true(st.min_ms == 1.0 && st.max_ms == 100.0);
    bench_stats_compute(x, 0, &st);
    assert_int_equal(st.n, 0);
    assert_true(st.median_ms == 0.0);
}

static void fill_result(struct bench_result *r)
{
    memset(r, 0, sizeof *r);
    snprintf(r->scene, sizeof r->scene, "rough \"storm\"\\x\n");
    snprintf(r->tier, sizeof r->tier, "gles2-min");
    snprintf(r->quality, sizeof r->quality, "high");
    snprintf(r->path, sizeof r->path, "1km");
    r->width = 1280;
    r->height = 720;
    r->frames = 100;
    r->frame.n = r->quad.n = 100;
    r->frame.median_ms = 12.5;
    r->quad.median_ms = 4.0;
    r->ratio = 3.125;
    r->bytes_gpu = 123456789012ull;
    r->cpu_valid = 0;
    r->cpu_instructions_per_frame = 1e6;
}

static void test_json(void **state)
{
    (void)state;
    struct bench_result r;
    fill_result(&r);
    char buf[8192];
    int n = bench_format_json(&r, buf, sizeof buf);
    assert_true(n > 0 && (size_t)n < sizeof buf);
    assert_int_equal((int)strlen(buf), n);
    assert_non_null(strstr(buf, "\"scene\": \"rough \\\"storm\\\"\\\\x\\u000a\","));
    assert_non_null(strstr(buf, "\"size\": \"1280x720\","));
    assert_non_null(strstr(buf, "\"ms_median\": 12.5,"));
    assert_non_null(strstr(buf, "\"baseline_quad_ms\": 4,"));
    assert_non_null(strstr(buf, "\"ratio\": 3.125,"));
    assert_non_null(strstr(buf, "\"cpu_instructions_per_frame\": null,"));
    assert_non_null(strstr(buf, "\"bytes_gpu\": 123456789012,"));
    assert_true(buf[0] == '{' && buf[n - 1] == '}');
    /* balanced quotes outside escapes: an even number of unescaped '"' */
    int quotes = 0;
    for (int i = 0; i < n; i++)
        if (buf[i] == '"' && (i == 0 || buf[i - 1] != '\\'))
            quotes++;
    assert_int_equal(quotes % 2, 0);

    r.cpu_valid = 1;
    r.frame.median_ms = NAN;
    n = bench_format_json(&r, buf, sizeof buf);
    assert_non_null(strstr(buf, "\"cpu_instructions_per_frame\": 1e+06,"));
    assert_non_null(strstr(buf, "\"ms_median\": null,"));

    /* truncation: the needed length is returned, nothing is written past cap */
    char small[64];
    memset(small, 'Z', sizeof small);
    int need = bench_format_json(&r, small, 32);
    assert_int_equal(need, n);
    assert_int_equal((int)strlen(small), 31);
    assert_true(small[40] == 'Z');
}

static void test_write_json_atomic(void **state)
{
    (void)state;
    const char *base = getenv("SWELL_TMP");
    char dir[96];
    snprintf(dir, sizeof dir, "%s/swell-test-bench.XXXXXX", base && base[0] ? base : "/tmp");
    assert_non_null(mkdtemp(dir));
    char path[128];
    snprintf(path, sizeof path, "%s/r.json", dir);
    struct bench_result r;
    fill_result(&r);
    struct swell_err err = { 0 };
    assert_int_equal(bench_write_json(path, &r, &err), 0);
    uint8_t *data = NULL;
    size_t len = 0;
    assert_int_equal(fs_read_file(path, 1 << 20, &data, &len, &err), 0);
    char buf[8192];
    int n = bench_format_json(&r, buf, sizeof buf);
    assert_int_equal((int)len, n + 1);
    assert_memory_equal(data, buf, (size_t)n);
    assert_int_equal(data[n], '\n');
    free(data);
    /* an unwritable place fails with a message naming it */
    char bad[192];
    snprintf(bad, sizeof bad, "%s/missing/dir/r.json", dir);
    assert_int_not_equal(bench_write_json(bad, &r, &err), 0);
    assert_non_null(strstr(err.msg, bad));
    unlink(path);
    rmdir(dir);
}

static volatile double sink;

static void work(int n)
{
    double s = 0;
    for (int i = 0; i < n; i++)
        s += (double)i * 0.5;
    sink = s;
}

static void test_counter(void **state)
{
    (void)state;
    struct bench_counter c;
    if (!bench_counter_open(&c)) {
        /* unavailable (no PMU, paranoid setting): must say why, and reading gives 0 */
        assert_int_equal(c.fd, -1);
        assert_true(strlen(c.why) > 20);
        bench_counter_start(&c);
        assert_true(bench_counter_stop(&c) == 0);
        bench_counter_close(&c);
        return;
    }
    bench_counter_start(&c);
    work(10000);
    uint64_t a = bench_counter_stop(&c);
    bench_counter_start(&c);
    work(1000000);
    uint64_t b = bench_counter_stop(&c);
    /* a loop iteration is a few instructions: 100x the iterations, roughly 100x the count */
    assert_true(a >= 10000 && b >= 1000000);
    assert_true(b > 30 * a);
    bench_counter_close(&c);
    bench_counter_close(&c);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_stats_against_definitions),
        cmocka_unit_test(test_stats_known_values),
        cmocka_unit_test(test_json),
        cmocka_unit_test(test_write_json_atomic),
        cmocka_unit_test(test_counter),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
