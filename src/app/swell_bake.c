/* swell-bake - bake a sea state into looping, self-describing tables, and inspect them.
 *
 *   swell-bake [--preset NAME]... [options] --out DIR [--report FILE.json]
 *   swell-bake inspect DIR
 *
 * main is a straight line: options -> sea state -> bake -> save -> report. Library code returns
 * errors; only this file prints and exits (0 ok, 1 runtime failure, 2 usage error).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <sys/stat.h>
#include <unistd.h>

#include "bake/bake.h"
#include "core/args.h"
#include "core/datadir.h"
#include "swell.h"
#include "core/fsutil.h"
#include "core/parse.h"
#include "core/preset.h"
#include "tables/budget.h"
#include "tables/tables_io.h"


struct options {
    struct seastate state;
    const char *out_dir;
    const char *report;
    int quiet;
};

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
    seastate_usage(f, 0);
    fprintf(f, "\nTables:\n");
    seastate_usage(f, 1);
    fprintf(f,
"\n"
"Output:\n"
"  --out DIR         directory for the KTX tables and manifest.swell (written atomically)\n"
"  --report FILE     write statistics as JSON (hs_m, mss, whitecap threshold and fractions, bytes)\n"
"  --quiet           no summary, no progress\n"
"  --help, --version\n\n");
    data_dir_usage(f);
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
    struct args args = { "swell-bake", argc, argv, 1, flags, valued, 1, usage,
                         "swell-bake " SWELL_VERSION_STRING };
    struct swell_err err = { 0 };
    struct seastate *s = &o->state;
    const char *a, *v;
    int r = 0, k;
    while (!r && (k = args_next(&args, &a, &v)) != ARGS_END) {
        if (k == ARGS_ERROR)
            return 2;
        if (k == ARGS_DONE)
            exit(0);
        if (!strcmp(a, "--quiet")) o->quiet = 1;
        else if (!strcmp(a, "--preset")) r = preset_load(v, s, &err);
        else if (!strcmp(a, "--out")) o->out_dir = v;
        else if (!strcmp(a, "--report")) o->report = v;
        else r = seastate_set_option(s, seastate_option(a), v, &err);
    }
    if (r) {
        fprintf(stderr, "swell-bake: %s\n", err.msg);
        return 2;
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

static double mss_resolved(const struct swell_tables *t, int axis)
{
    double m = 0.0;
    for (int i = 0; i < t->patterns; i++)
        m += axis ? t->pattern[i].mss_y : t->pattern[i].mss_x;
    return m;
}

static int write_report(const char *path, const struct swell_tables *t, double seconds,
                        struct swell_err *err)
{
    size_t cap = 16384, len = 0;
    char *buf = malloc(cap);
    if (!buf)
        return swell_fail(err, SWELL_E_NOMEM, "report buffer");
    double rx = mss_resolved(t, 0), ry = mss_resolved(t, 1);
    uint64_t tb = tables_bytes(t);
    uint64_t resident = budget_resident_bytes(t->patterns, t->state.size_fs);
#define OUT(...) len += (size_t)snprintf(buf + len, len < cap ? cap - len : 0, __VA_ARGS__)
    OUT("{\n  \"generator\": \"swell-bake " SWELL_VERSION_STRING "\",\n");
    OUT("  \"wind_speed_mps\": %.9g,\n  \"spectrum\": \"%s\",\n", t->state.wind_speed_mps,
        spectrum_name(t->state.spectrum));
    OUT("  \"hs_m\": %.9g,\n", t->hs_m);
    OUT("  \"mss_x\": %.9g,\n  \"mss_y\": %.9g,\n", rx + t->mss_unresolved_x,
        ry + t->mss_unresolved_y);
    OUT("  \"mss_resolved\": %.9g,\n  \"mss_unresolved\": %.9g,\n  \"mss_total\": %.9g,\n",
        rx + ry, (double)t->mss_unresolved_x + t->mss_unresolved_y,
        rx + ry + t->mss_unresolved_x + t->mss_unresolved_y);
    OUT("  \"whitecap_epsilon\": %.9g,\n  \"whitecap_breaking_fraction\": %.9g,\n"
        "  \"foam_recovery_per_s\": %.9g,\n", t->whitecap_epsilon,
        t->whitecap_breaking_fraction, t->foam_recovery_per_s);
    OUT("  \"whitecap_model\": \"%s\",\n", whitecap_model_name(t->state.whitecap_model));
    OUT("  \"whitecap_fraction_model\": %.9g,\n  \"whitecap_fraction_measured\": %.9g,\n",
        t->whitecap_fraction_model, t->whitecap_fraction_measured);
    OUT("  \"patterns\": %d,\n  \"frames\": %d,\n  \"loop_period_s\": %.9g,\n", t->patterns,
        t->frames, t->loop_period_s);
    OUT("  \"size_fs\": %d,\n  \"size_geo\": %d,\n", t->state.size_fs, t->state.size_geo);
    OUT("  \"pattern_sizes_m\": [");
    for (int i = 0; i < t->patterns; i++)
        OUT("%s%.9g", i ? ", " : "", t->pattern[i].size_m);
    OUT("],\n  \"bytes_tables\": %llu,\n  \"bytes_resident\": %llu,\n  \"bytes_gpu\": %llu,\n",
        (unsigned long long)tb, (unsigned long long)resident,
        (unsigned long long)(tb + resident));
    OUT("  \"budget_bytes\": %llu,\n  \"bake_seconds\": %.3f,\n",
        (unsigned long long)t->state.budget_bytes, seconds);
    OUT("  \"tables\": [\n");
    for (int i = 0; i < t->count; i++) {
        const struct swell_table *tb_i = &t->table[i];
        OUT("    {\"name\": \"%s\", \"kind\": \"%s\", \"pattern\": %d, \"format\": \"%s\", "
            "\"width\": %d, \"height\": %d, \"layers\": %d, \"levels\": %d, \"bytes\": %zu}%s\n",
            tb_i->name, table_kind_name(tb_i->kind), tb_i->pattern,
            table_format_name(tb_i->format), tb_i->width, tb_i->height, tb_i->layers,
            tb_i->levels, table_bytes(tb_i), i + 1 < t->count ? "," : "");
    }
    OUT("  ]\n}\n");
#undef OUT
    int r = 0;
    if (len >= cap)
        r = swell_fail(err, SWELL_E_ARG, "report larger than %zu bytes", cap);
    else
        r = fs_write_atomic(path, buf, len, err);
    free(buf);
    return r;
}

static void print_summary(const struct swell_tables *t, const char *dir, double seconds)
{
    double rx = mss_resolved(t, 0), ry = mss_resolved(t, 1);
    uint64_t tb = tables_bytes(t), res = budget_resident_bytes(t->patterns, t->state.size_fs);
    printf("swell-bake: %s, U10 %.1f m/s, fetch %.0f km: Hs %.2f m, mss %.4f (resolved %.4f)\n",
           spectrum_name(t->state.spectrum), t->state.wind_speed_mps, t->state.fetch_km, t->hs_m,
           rx + ry + t->mss_unresolved_x + t->mss_unresolved_y, rx + ry);
    printf("  %d patterns (", t->patterns);
    for (int i = 0; i < t->patterns; i++)
        printf("%s%.1f m", i ? ", " : "", t->pattern[i].size_m);
    printf("), %d frames over %.1f s, tables %dx%d / geometry %dx%d\n", t->frames,
           t->loop_period_s, t->state.size_fs, t->state.size_fs, t->state.size_geo,
           t->state.size_geo);
    printf("  whitecaps: epsilon %.4f on the summed k (breaking %.5f), foam recovers %.3g k/s; "
           "foam fraction %.5f vs %.5f %s\n", t->whitecap_epsilon,
           t->whitecap_breaking_fraction, t->foam_recovery_per_s,
           t->whitecap_fraction_measured, t->whitecap_fraction_model,
           whitecap_model_name(t->state.whitecap_model));
    printf("  memory: tables %llu bytes (held in RAM, streamed from; with the streamed part and a "
           "margin %llu); GPU at most %llu (any tier, geometry, quality); budget %llu\n",
           (unsigned long long)tb, (unsigned long long)(tb + res),
           (unsigned long long)budget_gpu_bytes(&t->state),
           (unsigned long long)t->state.budget_bytes);
    printf("  wrote %d tables to %s in %.2f s\n", t->count, dir, seconds);
}

static void inspect_row(void *user, const struct tables_verify_entry *e)
{
    int *bad = user;
    if (e->status)
        (*bad)++;
    printf("  %-18s %-9s %-6s %4dx%-4d layers %-3d levels %-2d %9llu B  %s%s%s\n", e->file,
           e->listed ? table_kind_name(e->kind) : "?", e->listed ? table_format_name(e->format) : "?",
           e->width, e->height, e->layers, e->levels, (unsigned long long)e->bytes,
           e->status ? "BAD: " : "ok", e->status ? e->msg : "", e->listed ? "" : " (not in manifest)");
}

static int cmd_inspect(int argc, char **argv)
{
    if (argc != 3 || argv[2][0] == '-') {
        fprintf(stderr, "usage: swell-bake inspect DIR\n");
        return 2;
    }
    struct swell_err err = { 0 };
    struct tables_manifest *m = calloc(1, sizeof *m);
    if (!m) {
        fprintf(stderr, "swell-bake: out of memory\n");
        return 1;
    }
    int bad = 0;
    printf("%s:\n", argv[2]);
    int r = tables_verify_dir(argv[2], inspect_row, &bad, m, &err);
    if (!r || bad) {
        const struct swell_tables *t = &m->set;
        uint64_t tb = 0;
        for (int i = 0; i < t->count; i++)
            tb += m->entry[i].file_bytes;
        printf("  sea state: %s, U10 %.1f m/s towards %.0f deg, fetch %.0f km, depth %s, seed %u\n",
               spectrum_name(t->state.spectrum), t->state.wind_speed_mps, t->state.wind_dir_deg,
               t->state.fetch_km, t->state.depth_m > 0 ? "finite" : "deep", t->state.seed);
        printf("  %d patterns, %d frames over %.1f s; Hs %.2f m; whitecaps %.5f (model %.5f)\n",
               t->patterns, t->frames, t->loop_period_s, t->hs_m, t->whitecap_fraction_measured,
               t->whitecap_fraction_model);
        printf("  memory: table files %llu bytes (held in RAM, streamed from); GPU at most %llu "
               "(any tier, geometry, quality); budget %llu\n", (unsigned long long)tb,
               (unsigned long long)budget_gpu_bytes(&t->state),
               (unsigned long long)t->state.budget_bytes);
    }
    free(m);
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
    struct bake_opts bo = { .progress = (!o.quiet && isatty(2)) ? on_progress : NULL, .user = &ps };
    struct swell_tables t;
    struct swell_err err = { 0 };
    r = swell_bake(&o.state, &bo, &t, &err);
    if (ps.shown)
        fprintf(stderr, "\n");
    if (r) {
        fprintf(stderr, "swell-bake: %s\n", err.msg);
        return r == SWELL_E_ARG ? 2 : 1;
    }
    double seconds = seconds_since(&ps.start);
    if ((r = tables_save_dir(&t, o.out_dir, &err)) ||
        (o.report && (r = write_report(o.report, &t, seconds, &err)))) {
        fprintf(stderr, "swell-bake: %s\n", err.msg);
        tables_destroy(&t);
        return 1;
    }
    if (!o.quiet)
        print_summary(&t, o.out_dir, seconds_since(&ps.start));
    tables_destroy(&t);
    return 0;
}
