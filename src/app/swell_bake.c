/* swell-bake - bake a sea state into looping, self-describing tables, and inspect them.
 *
 *   swell-bake [--preset NAME]... [options] --out DIR [--report FILE.json]
 *   swell-bake inspect DIR
 *
 * main is a straight line: options -> sea state -> bake -> save -> report. Library code returns
 * errors; only this file prints and exits (0 ok, 1 runtime failure, 2 usage error).
 * Built on the public API alone (include/swell.h), besides the command-line walk (core/args.h)
 * and the atomic file write (core/fsutil.h): tests/cli/test_public_api.sh checks its object
 * calls nothing else of the library.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <sys/stat.h>
#include <unistd.h>

#include "swell.h"
#include "core/args.h"
#include "core/fsutil.h"

/* the sea-state options as given, name and value pairs (swell_sea_desc options) */
#define MAX_SEA_ARGS 256

struct options {
    const char *sea[2 * MAX_SEA_ARGS + 1];
    int nsea;
    const char *out_dir;
    const char *report;
    int quiet;
};

/* One of swell_sea_usage's texts on f. */
static void print_usage_text(FILE *f, int what)
{
    size_t n = swell_sea_usage(what, NULL, 0);
    char *buf = malloc(n + 1);
    if (!buf)
        return;
    swell_sea_usage(what, buf, n + 1);
    fputs(buf, f);
    free(buf);
}

static void usage(FILE *f)
{
    fprintf(f,
"usage: swell-bake [options] --out DIR        bake a sea state into DIR\n"
"       swell-bake inspect DIR                 check and describe baked tables\n"
"\n"
"Sea state (every value has a unit; 0 or absent = the default shown):\n"
"  --preset NAME|FILE.preset  load a preset (calm, moderate, rough, storm; budgets tiny,\n"
"                             default; Data, below); may repeat; later options override it\n"
"");
    print_usage_text(f, SWELL_USAGE_SEA);
    fprintf(f, "\nTables:\n");
    print_usage_text(f, SWELL_USAGE_TABLES);
    fprintf(f,
"\n"
"Output:\n"
"  --out DIR         directory for the KTX tables and manifest.swell (written atomically)\n"
"  --report FILE     write statistics as JSON (hs_m, mss, whitecap threshold and fractions, bytes)\n"
"  --quiet           no summary, no progress\n"
"  --help, --version\n\n");
    print_usage_text(f, SWELL_USAGE_DATA);
}

/* The report's folder must exist before a bake starts, so a typo never fails after the
 * tables were written. 1 (with a message) when it does not. */
static int report_dir_missing(const char *path)
{
    char dir[4096];
    struct stat st;
    const char *slash = strrchr(path, '/');
    if (!path[0]) {
        fprintf(stderr, "swell-bake: --report: empty file name\n");
        return 1;
    }
    if (!slash)
        return 0;
    size_t n = slash == path ? 1 : (size_t)(slash - path);
    if (n >= sizeof dir) {
        fprintf(stderr, "swell-bake: --report: path too long\n");
        return 1;
    }
    memcpy(dir, path, n);
    dir[n] = '\0';
    if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode)) {
        fprintf(stderr, "swell-bake: --report: folder '%s' does not exist (create it first)\n",
                dir);
        return 1;
    }
    return 0;
}

/* path made absolute through its folder (which must exist): "/abs/dir/name"; 0 on failure. */
static int absolute(const char *path, char *out, size_t cap)
{
    char dir[4096], real[4096];
    const char *slash = strrchr(path, '/');
    size_t n = !slash ? 0 : slash == path ? 1 : (size_t)(slash - path);
    if (n >= sizeof dir)
        return 0;
    memcpy(dir, slash ? path : ".", slash ? n : 1);
    dir[slash ? n : 1] = '\0';
    if (!realpath(dir, real))
        return 0;
    int w = snprintf(out, cap, "%s/%s", strcmp(real, "/") ? real : "", slash ? slash + 1 : path);
    return w > 0 && (size_t)w < cap;
}

/* 1 (with a message) when the report would land in the set's folder, replace it, or land in
 * the folder the set is written in before it is swapped in (tables/set_dir.h): the set
 * replaces its whole folder, so a report there would be lost or block the next bake. */
static int report_collides(const char *report, const char *out)
{
    char r[8192], d[8192], real[4096];
    size_t n = strlen(out);
    while (n > 1 && out[n - 1] == '/')
        n--;
    char o[4096];
    snprintf(o, sizeof o, "%.*s", (int)n, out);
    if (!absolute(report, r, sizeof r))
        return 0;   /* its folder is checked to exist; nothing to compare then */
    if (realpath(o, real))
        snprintf(d, sizeof d, "%s", real);
    else if (!absolute(o, d, sizeof d))
        return 0;   /* out's folder does not exist yet: the report's (which does) is not in it */
    size_t dn = strlen(d);
    if (strcmp(r, d) == 0 || (strncmp(r, d, dn) == 0 && (r[dn] == '/' ||
                                                         strncmp(r + dn, ".tmp.", 5) == 0))) {
        fprintf(stderr, "swell-bake: --report '%s' is inside or is the table folder '%s'; a "
                "bake replaces that whole folder: write the report elsewhere\n", report, out);
        return 1;
    }
    return 0;
}

static int parse_args(int argc, char **argv, struct options *o)
{
    static const char *const flags[] = { "--quiet", NULL };
    static const char *const valued[] = { "--preset", "--out", "--report", NULL };
    struct args args = { "swell-bake", argc, argv, 1, flags, valued, swell_sea_option, usage,
                         "swell-bake " SWELL_VERSION_STRING };
    struct swell_err err = { 0 };
    const char *a, *v;
    int k;
    while ((k = args_next(&args, &a, &v)) != ARGS_END) {
        if (k == ARGS_ERROR)
            return 2;
        if (k == ARGS_DONE)
            exit(0);
        if (!strcmp(a, "--quiet")) o->quiet = 1;
        else if (!strcmp(a, "--out")) o->out_dir = v;
        else if (!strcmp(a, "--report")) o->report = v;
        else if (o->nsea == MAX_SEA_ARGS) {
            fprintf(stderr, "swell-bake: more than %d sea-state options\n", MAX_SEA_ARGS);
            return 2;
        } else {
            /* --preset and the sea state's options, in order: the sea's descriptor reads
             * them (a later one overrides an earlier) */
            o->sea[2 * o->nsea] = a;
            o->sea[2 * o->nsea + 1] = v;
            o->nsea++;
        }
    }
    o->sea[2 * o->nsea] = NULL;
    /* the first bad value named before anything is baked or written */
    swell_sea_desc d = { .options = o->sea };
    int r = swell_sea_check(&d, &err);
    if (r) {
        fprintf(stderr, "swell-bake: %s\n", err.msg);
        return r == SWELL_E_BUDGET ? 1 : 2;   /* a budget too small is found at bake time */
    }
    if (!o->out_dir) {
        fprintf(stderr, "swell-bake: --out DIR is required (see --help)\n");
        return 2;
    }
    if (o->report && (report_dir_missing(o->report) || report_collides(o->report, o->out_dir)))
        return 2;
    return 0;
}

struct progress_state {
    struct timespec start;
    int shown;
};

static double seconds_since(const struct timespec *t0)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)(t.tv_sec - t0->tv_sec) + 1e-9 * (double)(t.tv_nsec - t0->tv_nsec);
}

/* Progress on a TTY, only for bakes that take over a second. */
static void on_progress(void *user, double done, const char *stage)
{
    struct progress_state *p = user;
    if (seconds_since(&p->start) < 1.0)
        return;
    fprintf(stderr, "\rswell-bake: %-10s %3d%%", stage, (int)lround(done * 100.0));
    p->shown = 1;
}

static int write_report(const char *path, const swell_sea *sea, double seconds,
                        struct swell_err *err)
{
    size_t cap = 16384, len = 0;
    char *buf = malloc(cap);
    if (!buf) {
        snprintf(err->msg, sizeof err->msg, "no memory for the report");
        return err->code = SWELL_E_NOMEM;
    }
    swell_sea_info t;
    swell_sea_get_info(sea, &t);
    double rx = t.mss_resolved[0], ry = t.mss_resolved[1];
    double ux = t.mss_unresolved[0], uy = t.mss_unresolved[1];
#define OUT(...) len += (size_t)snprintf(buf + len, len < cap ? cap - len : 0, __VA_ARGS__)
    OUT("{\n  \"generator\": \"swell-bake " SWELL_VERSION_STRING "\",\n");
    OUT("  \"wind_speed_mps\": %.9g,\n  \"spectrum\": \"%s\",\n", t.wind_speed_mps, t.spectrum);
    OUT("  \"hs_m\": %.9g,\n", t.significant_height_m);
    OUT("  \"mss_x\": %.9g,\n  \"mss_y\": %.9g,\n", rx + ux, ry + uy);
    OUT("  \"mss_resolved\": %.9g,\n  \"mss_unresolved\": %.9g,\n  \"mss_total\": %.9g,\n",
        rx + ry, ux + uy, rx + ry + ux + uy);
    OUT("  \"whitecap_epsilon\": %.9g,\n  \"whitecap_breaking_fraction\": %.9g,\n"
        "  \"foam_recovery_per_s\": %.9g,\n", t.whitecap_epsilon, t.whitecap_breaking_fraction,
        t.foam_recovery_per_s);
    OUT("  \"whitecap_model\": \"%s\",\n", t.whitecap_model);
    OUT("  \"whitecap_fraction_model\": %.9g,\n  \"whitecap_fraction_measured\": %.9g,\n",
        t.whitecap_fraction_model, t.whitecap_fraction_measured);
    OUT("  \"patterns\": %d,\n  \"frames\": %d,\n  \"loop_period_s\": %.9g,\n", t.patterns,
        t.frames, t.loop_period_s);
    OUT("  \"size_fs\": %d,\n  \"size_geo\": %d,\n", t.table_size, t.geometry_size);
    OUT("  \"pattern_sizes_m\": [");
    for (int i = 0; i < t.patterns; i++)
        OUT("%s%.9g", i ? ", " : "", t.pattern_size_m[i]);
    OUT("],\n  \"bytes_tables\": %llu,\n  \"bytes_resident\": %llu,\n  \"bytes_gpu\": %llu,\n",
        (unsigned long long)t.table_bytes, (unsigned long long)t.resident_bytes,
        (unsigned long long)(t.table_bytes + t.resident_bytes));
    OUT("  \"budget_bytes\": %llu,\n  \"bake_seconds\": %.3f,\n",
        (unsigned long long)t.budget_bytes, seconds);
    OUT("  \"tables\": [\n");
    for (int i = 0; i < t.tables; i++) {
        swell_table_info ti;
        if (swell_sea_get_table(sea, i, &ti, err)) {
            free(buf);
            return err->code;
        }
        OUT("    {\"name\": \"%s\", \"kind\": \"%s\", \"pattern\": %d, \"format\": \"%s\", "
            "\"width\": %d, \"height\": %d, \"layers\": %d, \"levels\": %d, \"bytes\": %llu}%s\n",
            ti.name, ti.kind, ti.pattern, ti.format, ti.width, ti.height, ti.layers, ti.levels,
            (unsigned long long)ti.bytes, i + 1 < t.tables ? "," : "");
    }
    OUT("  ]\n}\n");
#undef OUT
    int r = 0;
    if (len >= cap) {
        snprintf(err->msg, sizeof err->msg, "report larger than %zu bytes", cap);
        r = err->code = SWELL_E_ARG;
    } else {
        r = fs_write_atomic(path, buf, len, err);
    }
    free(buf);
    return r;
}

static void print_summary(const swell_sea *sea, const char *dir, double seconds)
{
    swell_sea_info t;
    swell_sea_get_info(sea, &t);
    double rx = t.mss_resolved[0], ry = t.mss_resolved[1];
    printf("swell-bake: %s, U10 %.1f m/s, fetch %.0f km: Hs %.2f m, mss %.4f (resolved %.4f)\n",
           t.spectrum, t.wind_speed_mps, t.fetch_km, t.significant_height_m,
           rx + ry + t.mss_unresolved[0] + t.mss_unresolved[1], rx + ry);
    printf("  %d patterns (", t.patterns);
    for (int i = 0; i < t.patterns; i++)
        printf("%s%.1f m", i ? ", " : "", t.pattern_size_m[i]);
    printf("), %d frames over %.1f s, tables %dx%d / geometry %dx%d\n", t.frames,
           t.loop_period_s, t.table_size, t.table_size, t.geometry_size, t.geometry_size);
    printf("  whitecaps: epsilon %.4f on the summed k (breaking %.5f), foam recovers %.3g k/s; "
           "foam fraction %.5f vs %.5f %s\n", t.whitecap_epsilon,
           t.whitecap_breaking_fraction, t.foam_recovery_per_s,
           t.whitecap_fraction_measured, t.whitecap_fraction_model, t.whitecap_model);
    printf("  memory: tables %llu bytes (held in RAM, streamed from; with the streamed part and a "
           "margin %llu); GPU at most %llu (any tier, geometry, quality); budget %llu\n",
           (unsigned long long)t.table_bytes, (unsigned long long)(t.table_bytes + t.resident_bytes),
           (unsigned long long)t.gpu_bytes_max, (unsigned long long)t.budget_bytes);
    printf("  wrote %d tables to %s in %.2f s\n", t.tables, dir, seconds);
}

static void inspect_row(void *user, const swell_table_info *e, int listed, int status,
                        const char *msg)
{
    int *bad = user;
    if (status)
        (*bad)++;
    printf("  %-18s %-9s %-6s %4dx%-4d layers %-3d levels %-2d %9llu B  %s%s%s\n", e->name,
           e->kind, e->format, e->width, e->height, e->layers, e->levels,
           (unsigned long long)e->bytes, status ? "BAD: " : "ok", status ? msg : "",
           listed ? "" : " (not in manifest)");
}

static int cmd_inspect(int argc, char **argv)
{
    if (argc != 3 || argv[2][0] == '-') {
        fprintf(stderr, "usage: swell-bake inspect DIR\n");
        return 2;
    }
    struct swell_err err = { 0 };
    swell_sea_info t;
    int bad = 0;
    printf("%s:\n", argv[2]);
    int r = swell_sea_check_dir(argv[2], inspect_row, &bad, &t, &err);
    if (t.patterns > 0) {
        printf("  sea state: %s, U10 %.1f m/s towards %.0f deg, fetch %.0f km, depth %s, seed %u\n",
               t.spectrum, t.wind_speed_mps, t.wind_dir_deg, t.fetch_km,
               t.depth_m > 0 ? "finite" : "deep", t.seed);
        printf("  %d patterns, %d frames over %.1f s; Hs %.2f m; whitecaps %.5f (model %.5f)\n",
               t.patterns, t.frames, t.loop_period_s, t.significant_height_m,
               t.whitecap_fraction_measured, t.whitecap_fraction_model);
        printf("  memory: table files %llu bytes (held in RAM, streamed from); GPU at most %llu "
               "(any tier, geometry, quality); budget %llu\n", (unsigned long long)t.table_bytes,
               (unsigned long long)t.gpu_bytes_max, (unsigned long long)t.budget_bytes);
    }
    if (r) {
        fprintf(stderr, "swell-bake: inspect %s: %s\n", argv[2], err.msg);
        return 1;
    }
    printf("  all tables sound\n");
    return 0;
}

int main(int argc, char **argv)
{
    if (argc >= 2 && !strcmp(argv[1], "inspect"))
        return cmd_inspect(argc, argv);

    struct options o = { 0 };
    int r = parse_args(argc, argv, &o);
    if (r)
        return r;

    struct progress_state ps = { 0 };
    clock_gettime(CLOCK_MONOTONIC, &ps.start);
    swell_sea_desc d = { .options = o.sea,
                         .progress = (!o.quiet && isatty(2)) ? on_progress : NULL,
                         .progress_user = &ps };
    swell_sea *sea = NULL;
    struct swell_err err = { 0 };
    r = swell_sea_bake(&d, &sea, &err);
    if (ps.shown)
        fprintf(stderr, "\n");
    if (r) {
        fprintf(stderr, "swell-bake: %s\n", err.msg);
        return r == SWELL_E_ARG ? 2 : 1;
    }
    double seconds = seconds_since(&ps.start);
    if ((r = swell_sea_save(sea, o.out_dir, &err)) ||
        (o.report && (r = write_report(o.report, sea, seconds, &err)))) {
        fprintf(stderr, "swell-bake: %s\n", err.msg);
        swell_sea_destroy(sea);
        return 1;
    }
    if (!o.quiet)
        print_summary(sea, o.out_dir, seconds_since(&ps.start));
    swell_sea_destroy(sea);
    return 0;
}
