/* kms_probe.c - the KMS test's own client: drives the platform layer (platform_open with
 * PLATFORM_KMS, or surfaceless) with frames whose every pixel is known in advance, and checks
 * what the display scanned out against that CPU reference.
 *
 *   kms_probe run [--platform kms|surfaceless] [--frames N] [--mode WxH[@Hz]] [--size WxH]
 *                 [--api auto|atomic|legacy] [--connector NAME] [--out FILE.ppm] [--verbose]
 *                 [--max-fps F] [--min-frames M] [--mark FILE]
 *       N frames (0 = until SIGINT/SIGTERM). Frame f is a clear colour plus one scissored
 *       rectangle, both exact multiples of 1/255 so the 8-bit result is exact. Every frame whose
 *       index is a multiple of 16, and the last one, is read back (read_rgba: on KMS the buffer the
 *       CRTC shows) and compared pixel by pixel with the reference; then the display state
 *       read through a second, non-master fd after platform_close() must equal the state before
 *       platform_open() (saved CRTC restored). Prints the frame rate (with --max-fps, faster
 *       than F fails: flips must wait for vblank; fewer than M frames fails, which makes a
 *       signal test meaningful; --mark creates FILE once M frames were presented, so a test
 *       knows when to send the signal); exit 0 only if all holds.
 *   kms_probe compare A B [--max-diff N] [--radius R] [--max-percent P] [--max-mean M]
 *       0 when two images (.png or binary .ppm) have the same size, at most P % of the pixels
 *       differ at all, the mean absolute channel difference is at most M, and every pixel of
 *       each image has a pixel of the other within R pixels whose RGB channels differ by at
 *       most N. Defaults 0: bit-identical.
 *   kms_probe watch [--term-after S | --term-when-exists FILE] [--connector NAME] -- CMD...
 *       runs another program (build/rel/swell) under the same display-restore check.
 */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include <GLES2/gl2.h>
#include <png.h>
#include <signal.h>
#include <sys/wait.h>
#include <xf86drm.h>
#include <xf86drmMode.h>

#include "platform/platform.h"

struct crtc_state {
    int valid;
    uint32_t crtc_id, fb_id, x, y, w, h, mode_valid;
    char mode_name[DRM_DISPLAY_MODE_LEN];
};

struct colour { uint8_t r, g, b; };
struct rect { int x, y, w, h; };    /* GL window coordinates: y from the bottom */

static struct colour bg_of(int f)
{
    return (struct colour){ (uint8_t)(f * 37 + 11), (uint8_t)(f * 91 + 7),
                            (uint8_t)(f * 13 + 200) };
}

static struct colour fg_of(int f)
{
    return (struct colour){ (uint8_t)(255 - f * 5), (uint8_t)(f * 17), (uint8_t)(90 + f * 3) };
}

static struct rect rect_of(int f, int w, int h)
{
    return (struct rect){ (f * 7) % (w / 2), (f * 3) % (h / 2), w / 3, h / 5 };
}

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + t.tv_nsec * 1e-9;
}

static void draw(int f, int w, int h)
{
    struct colour bg = bg_of(f), fg = fg_of(f);
    struct rect r = rect_of(f, w, h);
    glDisable(GL_SCISSOR_TEST);
    glClearColor(bg.r / 255.0f, bg.g / 255.0f, bg.b / 255.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_SCISSOR_TEST);
    glScissor(r.x, r.y, r.w, r.h);
    glClearColor(fg.r / 255.0f, fg.g / 255.0f, fg.b / 255.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glDisable(GL_SCISSOR_TEST);
}

/* Counts pixels that differ from the reference of frame f (rgba top row first). */
static long check(const uint8_t *rgba, int f, int w, int h, char *first, size_t n)
{
    struct colour bg = bg_of(f), fg = fg_of(f);
    struct rect r = rect_of(f, w, h);
    long bad = 0;
    first[0] = '\0';
    for (int row = 0; row < h; row++) {
        int gy = h - 1 - row;
        for (int x = 0; x < w; x++) {
            int in = x >= r.x && x < r.x + r.w && gy >= r.y && gy < r.y + r.h;
            struct colour c = in ? fg : bg;
            const uint8_t *px = rgba + ((size_t)row * w + x) * 4;
            if (px[0] != c.r || px[1] != c.g || px[2] != c.b || px[3] != 255) {
                if (!bad++)
                    snprintf(first, n, "pixel (%d,%d) is %u,%u,%u,%u, expected %u,%u,%u,255", x,
                             row, px[0], px[1], px[2], px[3], c.r, c.g, c.b);
            }
        }
    }
    return bad;
}

static int write_ppm(const char *path, const uint8_t *rgba, int w, int h)
{
    FILE *fp = fopen(path, "wb");
    if (!fp)
        return -1;
    fprintf(fp, "P6\n%d %d\n255\n", w, h);
    for (size_t i = 0; i < (size_t)w * h; i++)
        fwrite(rgba + 4 * i, 1, 3, fp);
    return fclose(fp);
}

static uint8_t *read_ppm(const char *path, int *w, int *h);

/* RGB8 pixels of a PNG (libpng's simplified API) or binary PPM file; NULL when unreadable. */
static uint8_t *read_image(const char *path, int *w, int *h)
{
    size_t n = strlen(path);
    if (n < 4 || strcmp(path + n - 4, ".png") != 0)
        return read_ppm(path, w, h);
    png_image img;
    memset(&img, 0, sizeof img);
    img.version = PNG_IMAGE_VERSION;
    if (!png_image_begin_read_from_file(&img, path))
        return NULL;
    img.format = PNG_FORMAT_RGB;
    uint8_t *px = malloc(PNG_IMAGE_SIZE(img));
    if (!px || !png_image_finish_read(&img, NULL, px, 0, NULL)) {
        png_image_free(&img);
        free(px);
        return NULL;
    }
    *w = (int)img.width;
    *h = (int)img.height;
    return px;
}

static uint8_t *read_ppm(const char *path, int *w, int *h)
{
    FILE *fp = fopen(path, "rb");
    if (!fp)
        return NULL;
    int maxv = 0;
    uint8_t *px = NULL;
    if (fscanf(fp, "P6 %d %d %d", w, h, &maxv) == 3 && maxv == 255 && fgetc(fp) != EOF &&
        *w > 0 && *h > 0 && *w < 65536 && *h < 65536) {
        size_t n = (size_t)*w * *h * 3;
        px = malloc(n);
        if (px && fread(px, 1, n, fp) != n) {
            free(px);
            px = NULL;
        }
    }
    fclose(fp);
    return px;
}

/* Largest over pixels of A of the smallest max-channel difference to B within a
 * (2r+1)^2 window: how far A is from B when content may move by up to r pixels. */
static int neighbour_diff(const uint8_t *a, const uint8_t *b, int w, int h, int r)
{
    int worst = 0;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            const uint8_t *pa = a + ((size_t)y * w + x) * 3;
            int best = 256;
            for (int dy = -r; dy <= r && best > 0; dy++)
                for (int dx = -r; dx <= r && best > 0; dx++) {
                    int yy = y + dy, xx = x + dx;
                    if (yy < 0 || yy >= h || xx < 0 || xx >= w)
                        continue;
                    const uint8_t *pb = b + ((size_t)yy * w + xx) * 3;
                    int d = 0;
                    for (int k = 0; k < 3; k++)
                        d = abs(pa[k] - pb[k]) > d ? abs(pa[k] - pb[k]) : d;
                    best = d < best ? d : best;
                }
            worst = best > worst ? best : worst;
        }
    return worst;
}

static int compare_main(int argc, char **argv)
{
    int tol = 0, radius = 0;
    double max_pct = 0, max_mean = 0;
    if (argc < 4 || argc % 2) {
        fprintf(stderr, "usage: kms_probe compare A B [--max-diff N] [--radius R] "
                        "[--max-percent P] [--max-mean M]\n");
        return 2;
    }
    for (int i = 4; i + 1 < argc; i += 2) {
        if (!strcmp(argv[i], "--max-diff"))
            tol = atoi(argv[i + 1]);
        else if (!strcmp(argv[i], "--radius"))
            radius = atoi(argv[i + 1]);
        else if (!strcmp(argv[i], "--max-percent"))
            max_pct = atof(argv[i + 1]);
        else if (!strcmp(argv[i], "--max-mean"))
            max_mean = atof(argv[i + 1]);
        else
            return fprintf(stderr, "kms_probe compare: unknown option %s\n", argv[i]), 2;
    }
    int wa, ha, wb, hb;
    uint8_t *a = read_image(argv[2], &wa, &ha), *b = read_image(argv[3], &wb, &hb);
    int rc = 1;
    if (!a || !b) {
        fprintf(stderr, "kms_probe compare: cannot read %s\n", !a ? argv[2] : argv[3]);
    } else if (wa != wb || ha != hb) {
        fprintf(stderr, "kms_probe compare: sizes differ: %dx%d vs %dx%d\n", wa, ha, wb, hb);
    } else {
        long differ = 0;
        int maxd = 0;
        double sum = 0;
        for (size_t i = 0; i < (size_t)wa * ha; i++) {
            int d = 0;
            for (int k = 0; k < 3; k++) {
                int c = abs((int)a[3 * i + k] - (int)b[3 * i + k]);
                d = c > d ? c : d;
                sum += c;
            }
            maxd = d > maxd ? d : maxd;
            differ += d > 0;
        }
        double pct = 100.0 * differ / ((double)wa * ha);
        int nd = radius > 0 ? neighbour_diff(a, b, wa, ha, radius) : maxd;
        int nd2 = radius > 0 ? neighbour_diff(b, a, wa, ha, radius) : maxd;
        nd = nd2 > nd ? nd2 : nd;
        double mean = sum / ((double)wa * ha * 3);
        printf("kms_probe compare: %dx%d, %.3f%% of pixels differ (allowed %.3f%%), mean channel "
               "difference %.4f (allowed %.4f), max %d; within %d px max %d (allowed %d)\n", wa,
               ha, pct, max_pct, mean, max_mean, maxd, radius, nd, tol);
        rc = nd <= tol && pct <= max_pct && mean <= max_mean ? 0 : 1;
    }
    free(a);
    free(b);
    return rc;
}

/* The first connected connector's CRTC as a non-master client sees it. */
static struct crtc_state read_state(int fd, const char *connector)
{
    struct crtc_state s = { 0 };
    drmModeRes *res = drmModeGetResources(fd);
    if (!res)
        return s;
    for (int i = 0; i < res->count_connectors && !s.valid; i++) {
        drmModeConnector *c = drmModeGetConnector(fd, res->connectors[i]);
        if (!c)
            continue;
        char name[64];
        const char *t = drmModeGetConnectorTypeName(c->connector_type);
        snprintf(name, sizeof name, "%s-%u", t ? t : "Unknown", c->connector_type_id);
        if (c->connection == DRM_MODE_CONNECTED && (!connector || !strcmp(connector, name))) {
            s.valid = 1;
            drmModeEncoder *e = c->encoder_id ? drmModeGetEncoder(fd, c->encoder_id) : NULL;
            s.crtc_id = e ? e->crtc_id : 0;
            drmModeFreeEncoder(e);
            drmModeCrtc *cr = s.crtc_id ? drmModeGetCrtc(fd, s.crtc_id) : NULL;
            if (cr) {
                s.fb_id = cr->buffer_id;
                s.x = cr->x;
                s.y = cr->y;
                s.mode_valid = (uint32_t)cr->mode_valid;
                s.w = cr->mode.hdisplay;
                s.h = cr->mode.vdisplay;
                memcpy(s.mode_name, cr->mode.name, sizeof s.mode_name);
                drmModeFreeCrtc(cr);
            }
        }
        drmModeFreeConnector(c);
    }
    drmModeFreeResources(res);
    return s;
}

static void print_state(const char *when, const struct crtc_state *s)
{
    printf("kms_probe: display %s: crtc %u fb %u at %u,%u mode %s %ux%u\n", when, s->crtc_id,
           s->fb_id, s->x, s->y, s->mode_valid ? s->mode_name : "(none)", s->w, s->h);
}

static int parse_wh(const char *s, int *w, int *h, int *hz)
{
    *hz = 0;
    int n = sscanf(s, "%dx%d@%d", w, h, hz);
    return n >= 2 && *w > 0 && *h > 0 ? 0 : -1;
}

static int run_main(int argc, char **argv)
{
    struct platform_desc d = { .kind = PLATFORM_KMS, .width = 640, .height = 480 };
    int frames = 60;
    double max_fps = 0;
    int min_frames = 0;
    const char *mark = NULL;
    const char *out = NULL;
    for (int i = 2; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        int used = 1;
        if (!strcmp(a, "--verbose")) {
            d.verbose = 1;
            used = 0;
        } else if (!v) {
            fprintf(stderr, "kms_probe: %s needs a value\n", a);
            return 2;
        } else if (!strcmp(a, "--platform")) {
            d.kind = !strcmp(v, "surfaceless") ? PLATFORM_SURFACELESS : PLATFORM_KMS;
        } else if (!strcmp(a, "--frames")) {
            frames = atoi(v);
        } else if (!strcmp(a, "--mode")) {
            if (parse_wh(v, &d.mode_w, &d.mode_h, &d.mode_hz))
                return fprintf(stderr, "kms_probe: bad --mode %s\n", v), 2;
        } else if (!strcmp(a, "--size")) {
            int hz;
            if (parse_wh(v, &d.width, &d.height, &hz))
                return fprintf(stderr, "kms_probe: bad --size %s\n", v), 2;
        } else if (!strcmp(a, "--api")) {
            d.kms_api = !strcmp(v, "atomic") ? KMS_API_ATOMIC
                      : !strcmp(v, "legacy") ? KMS_API_LEGACY : KMS_API_AUTO;
        } else if (!strcmp(a, "--connector")) {
            d.connector = v;
        } else if (!strcmp(a, "--mark")) {
            mark = v;
        } else if (!strcmp(a, "--min-frames")) {
            min_frames = atoi(v);
        } else if (!strcmp(a, "--max-fps")) {
            max_fps = atof(v);
        } else if (!strcmp(a, "--out")) {
            out = v;
        } else {
            fprintf(stderr, "kms_probe: unknown option %s\n", a);
            return 2;
        }
        i += used;
    }

    /* A second client on the same device, opened first and then stripped of master so the
     * back-end can take it: it keeps the device open across platform_close(), so the state it
     * reads afterwards is what destroy() restored, not the kernel's last-close fbdev restore. */
    int mon = -1;
    struct crtc_state before = { 0 };
    if (d.kind == PLATFORM_KMS) {
        /* When this fails platform_open() below says why (no device, permissions). */
        mon = open(d.device ? d.device : "/dev/dri/card0", O_RDWR | O_CLOEXEC);
        if (mon >= 0) {
            if (drmIsMaster(mon))
                drmDropMaster(mon);
            before = read_state(mon, d.connector);
            print_state("before", &before);
        }
    }

    struct swell_err err = { 0 };
    struct platform_handle h;
    if (platform_open(&d, &h, &err)) {
        fprintf(stderr, "kms_probe: %s\n", err.msg);
        return 1;
    }
    int w = 0, hh = 0;
    h.be->size(h.p, &w, &hh);
    printf("kms_probe: platform %s, %dx%d\n", h.be->name, w, hh);
    if (d.verbose && !h.be->begin_frame(h.p, &err)) {
        GLint bits[6] = { 0 };
        const GLenum q[6] = { GL_RED_BITS, GL_GREEN_BITS, GL_BLUE_BITS, GL_ALPHA_BITS,
                              GL_DEPTH_BITS, GL_STENCIL_BITS };
        for (int i = 0; i < 6; i++)
            glGetIntegerv(q[i], &bits[i]);
        printf("kms_probe: GL %s, framebuffer R%dG%dB%dA%d depth %d stencil %d\n",
               (const char *)glGetString(GL_VERSION), bits[0], bits[1], bits[2], bits[3],
               bits[4], bits[5]);
    }
    uint8_t *rgba = malloc((size_t)w * hh * 4);
    int rc = rgba ? 0 : 1;
    int f = 0, checked = 0;
    long bad_total = 0;
    double t_first = 0;
    while (!rc && (frames <= 0 || f < frames) && !h.be->should_quit(h.p)) {
        rc = h.be->begin_frame(h.p, &err);
        if (!rc) {
            draw(f, w, hh);
            rc = h.be->present(h.p, &err);
        }
        if (rc)
            break;
        if (f == 0)
            t_first = now_s();
        if (mark && f + 1 == (min_frames > 0 ? min_frames : 1)) {
            FILE *m = fopen(mark, "w");
            if (m)
                fclose(m);
        }
        int last = frames > 0 && f == frames - 1;
        if (f % 16 == 0 || last) {
            char first[160];
            rc = h.be->read_rgba(h.p, rgba, &err);
            if (rc)
                break;
            long bad = check(rgba, f, w, hh, first, sizeof first);
            checked++;
            if (bad)
                printf("kms_probe: frame %d: %ld pixels differ from the reference; first: %s\n",
                       f, bad, first);
            bad_total += bad;
        }
        f++;
    }
    double t1 = now_s();
    int quit = h.be->should_quit(h.p);
    if (rc)
        fprintf(stderr, "kms_probe: frame %d: %s\n", f, err.msg);
    if (!rc && out && f > 0) {
        rc = h.be->read_rgba(h.p, rgba, &err);
        if (!rc && write_ppm(out, rgba, w, hh)) {
            fprintf(stderr, "kms_probe: cannot write %s\n", out);
            rc = 1;
        }
    }
    platform_close(&h);
    free(rgba);
    if (f < min_frames) {
        printf("kms_probe: FAIL: only %d frames presented, expected at least %d\n", f,
               min_frames);
        rc = 1;
    }
    if (f > 1)
        printf("kms_probe: %d frames, %.1f frames/s after the first (%.2f ms per frame)%s\n", f,
               (f - 1) / (t1 - t_first), 1e3 * (t1 - t_first) / (f - 1),
               quit ? ", stopped by signal" : "");
    printf("kms_probe: %d frames checked, %ld pixels wrong in total\n", checked, bad_total);
    if (max_fps > 0 && f > 1 && (f - 1) / (t1 - t_first) > max_fps) {
        printf("kms_probe: FAIL: faster than %.0f frames/s: flips are not paced by vblank\n",
               max_fps);
        rc = 1;
    }
    if (bad_total)
        rc = 1;
    if (d.kind == PLATFORM_KMS && mon < 0) {
        printf("kms_probe: FAIL: could not open a monitoring fd, restore not checked\n");
        rc = 1;
    } else if (mon >= 0) {
        struct crtc_state after = read_state(mon, d.connector);
        print_state("after", &after);
        if (memcmp(&before, &after, sizeof before) != 0) {
            printf("kms_probe: FAIL: the display state was not restored\n");
            rc = 1;
        } else {
            printf("kms_probe: display state restored\n");
        }
        close(mon);
    }
    if (frames > 0 && f != frames && !quit)
        rc = 1;
    return rc ? 1 : 0;
}

/* kms_probe watch [--term-after S | --term-when-exists FILE] [--connector NAME] -- CMD ARGS...
 * Runs CMD while holding a non-master fd on /dev/dri/card0 (so the kernel's last-close fbdev
 * restore cannot hide a missing restore), optionally sends it SIGTERM after S seconds or once
 * FILE exists (e.g. the PNG of a frame that was flipped: certainly mid-run), and
 * exits 0 only if CMD exited 0 and the display state afterwards equals the state before. */
static int watch_main(int argc, char **argv)
{
    double term_after = 0;
    const char *connector = NULL, *term_when = NULL;
    int i = 2;
    for (; i < argc && strcmp(argv[i], "--"); i++) {
        if (!strcmp(argv[i], "--term-after") && i + 1 < argc)
            term_after = atof(argv[++i]);
        else if (!strcmp(argv[i], "--term-when-exists") && i + 1 < argc)
            term_when = argv[++i];
        else if (!strcmp(argv[i], "--connector") && i + 1 < argc)
            connector = argv[++i];
    }
    if (i + 1 >= argc) {
        fprintf(stderr, "usage: kms_probe watch [--term-after S] [--connector N] -- CMD...\n");
        return 2;
    }
    char **cmd = argv + i + 1;
    int mon = open("/dev/dri/card0", O_RDWR | O_CLOEXEC);
    if (mon < 0) {
        fprintf(stderr, "kms_probe watch: /dev/dri/card0: %s\n", strerror(errno));
        return 1;
    }
    if (drmIsMaster(mon))
        drmDropMaster(mon);
    struct crtc_state before = read_state(mon, connector);
    print_state("before", &before);
    fflush(stdout);
    pid_t pid = fork();
    if (pid == 0) {
        execvp(cmd[0], cmd);
        fprintf(stderr, "kms_probe watch: cannot run %s: %s\n", cmd[0], strerror(errno));
        _exit(127);
    }
    int status = 0, rc = 1;
    if (pid > 0) {
        if (term_after > 0 || term_when) {
            /* Poll (10 Hz) for the trigger; the program ending first is a failure. */
            double t0 = now_s();
            int ended = 0;
            while (!(ended = waitpid(pid, &status, WNOHANG) != 0)) {
                if (term_when ? access(term_when, F_OK) == 0 : now_s() - t0 >= term_after)
                    break;
                struct timespec t = { 0, 100000000 };
                nanosleep(&t, NULL);
            }
            if (!ended) {
                kill(pid, SIGTERM);
                printf("kms_probe watch: sent SIGTERM after %.1f s%s%s\n", now_s() - t0,
                       term_when ? ", when this appeared: " : "", term_when ? term_when : "");
            } else {
                printf("kms_probe watch: FAIL: the program ended before SIGTERM was sent\n");
                close(mon);
                return 1;
            }
        }
        while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
        }
        rc = WIFEXITED(status) && WEXITSTATUS(status) == 0 ? 0 : 1;
        printf("kms_probe watch: program %s %d\n", WIFEXITED(status) ? "exited with" : "killed by",
               WIFEXITED(status) ? WEXITSTATUS(status) : WTERMSIG(status));
    }
    struct crtc_state after = read_state(mon, connector);
    print_state("after", &after);
    if (memcmp(&before, &after, sizeof before) != 0) {
        printf("kms_probe watch: FAIL: the display state was not restored\n");
        rc = 1;
    }
    close(mon);
    return rc;
}

int main(int argc, char **argv)
{
    if (argc >= 2 && !strcmp(argv[1], "watch"))
        return watch_main(argc, argv);
    if (argc >= 2 && !strcmp(argv[1], "run"))
        return run_main(argc, argv);
    if (argc >= 2 && !strcmp(argv[1], "compare"))
        return compare_main(argc, argv);
    fprintf(stderr, "usage: kms_probe run [options] | compare A B [options] | "
                    "watch [opts] -- CMD...\n"
                    "(see the comment at the top of tests/kms/kms_probe.c)\n");
    return 2;
}
