/* input.c - keyboard through libinput (input.h): key bindings, camera and sun steps, and the
 * libinput/udev context, which is optional by design: a kiosk without a keyboard, a container
 * without /dev/input or a user without permission still gets its frames. */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <termios.h>
#include <unistd.h>

#include <libinput.h>
#include <libudev.h>
#include <linux/input-event-codes.h>

#include "platform/input.h"

#define INPUT_PI 3.14159265358979323846
#define DEFAULT_SEAT "seat0"
#define SEAT_MAX 64

/* ---- bindings ---------------------------------------------------------------------------- */

enum bind_kind { BIND_HOLD, BIND_QUIT, BIND_SCREENSHOT, BIND_PRESET, BIND_BOAT };

struct binding {
    uint16_t code;      /* evdev KEY_* */
    uint8_t kind;       /* enum bind_kind */
    uint8_t arg;        /* HOLD: enum input_hold; PRESET: enum input_preset */
    uint8_t bit;        /* HOLD: which of the action's keys (bit in input_state.held) */
};

static const struct binding bindings[] = {
    { KEY_ESC,       BIND_QUIT,       0, 0 },
    { KEY_Q,         BIND_QUIT,       0, 0 },
    { KEY_W,         BIND_HOLD,       INPUT_HOLD_FORWARD,    0 },
    { KEY_UP,        BIND_HOLD,       INPUT_HOLD_FORWARD,    1 },
    { KEY_S,         BIND_HOLD,       INPUT_HOLD_BACK,       0 },
    { KEY_DOWN,      BIND_HOLD,       INPUT_HOLD_BACK,       1 },
    { KEY_A,         BIND_HOLD,       INPUT_HOLD_TURN_LEFT,  0 },
    { KEY_LEFT,      BIND_HOLD,       INPUT_HOLD_TURN_LEFT,  1 },
    { KEY_D,         BIND_HOLD,       INPUT_HOLD_TURN_RIGHT, 0 },
    { KEY_RIGHT,     BIND_HOLD,       INPUT_HOLD_TURN_RIGHT, 1 },
    { KEY_PAGEUP,    BIND_HOLD,       INPUT_HOLD_PITCH_UP,   0 },
    { KEY_PAGEDOWN,  BIND_HOLD,       INPUT_HOLD_PITCH_DOWN, 0 },
    { KEY_RIGHTBRACE, BIND_HOLD,      INPUT_HOLD_SUN_UP,     0 },
    { KEY_LEFTBRACE, BIND_HOLD,       INPUT_HOLD_SUN_DOWN,   0 },
    { KEY_1,         BIND_PRESET,     INPUT_PRESET_CALM,     0 },
    { KEY_2,         BIND_PRESET,     INPUT_PRESET_MODERATE, 0 },
    { KEY_3,         BIND_PRESET,     INPUT_PRESET_ROUGH,    0 },
    { KEY_4,         BIND_PRESET,     INPUT_PRESET_STORM,    0 },
    { KEY_F12,       BIND_SCREENSHOT, 0, 0 },
    { KEY_P,         BIND_SCREENSHOT, 0, 0 },
    { KEY_B,         BIND_BOAT,       0, 0 },
};

/* The names of the shipped presets in tables/ (tables/<name>.preset). */
static const char *const preset_names[INPUT_PRESET_COUNT] = {
    "calm", "moderate", "rough", "storm",
};

void input_state_init(struct input_state *st)
{
    memset(st, 0, sizeof(*st));
    st->preset = INPUT_PRESET_NONE;
}

void input_clear_edges(struct input_state *st)
{
    st->screenshot = 0;
    st->boat = 0;
    st->preset = INPUT_PRESET_NONE;
}

void input_apply_key(struct input_state *st, uint32_t linux_keycode, int pressed)
{
    /* Autorepeat would re-fire the one-shots; held actions need no repeat. */
    if (pressed != 0 && pressed != 1)
        return;
    for (size_t i = 0; i < sizeof bindings / sizeof bindings[0]; i++) {
        const struct binding *b = &bindings[i];
        if (b->code != linux_keycode)
            continue;
        switch (b->kind) {
        case BIND_HOLD:
            if (pressed)
                st->held[b->arg] |= (uint8_t)(1u << b->bit);
            else
                st->held[b->arg] &= (uint8_t)~(1u << b->bit);
            break;
        case BIND_QUIT:
            if (pressed)
                st->quit = 1;
            break;
        case BIND_SCREENSHOT:
            if (pressed)
                st->screenshot = 1;
            break;
        case BIND_PRESET:
            if (pressed)
                st->preset = b->arg;
            break;
        case BIND_BOAT:
            if (pressed)
                st->boat = 1;
            break;
        default:
            break;
        }
        return;
    }
}

int input_held(const struct input_state *st, int hold)
{
    return hold >= 0 && hold < INPUT_HOLD_COUNT && st->held[hold] != 0;
}

const char *input_preset_name(int preset)
{
    return preset >= 0 && preset < INPUT_PRESET_COUNT ? preset_names[preset] : "none";
}

/* ---- motion ------------------------------------------------------------------------------ */

static double clamp_d(double x, double lo, double hi)
{
    return x < lo ? lo : (x > hi ? hi : x);
}

static double clamp_dt(double dt_s)
{
    /* !(dt > 0) also catches NaN. */
    return !(dt_s > 0.0) ? 0.0 : (dt_s > INPUT_DT_MAX_S ? INPUT_DT_MAX_S : dt_s);
}

/* +1, -1 or 0 from a pair of opposite held actions. */
static int axis(const struct input_state *st, int plus, int minus)
{
    return input_held(st, plus) - input_held(st, minus);
}

void input_camera_step(const struct input_state *st, double dt_s, struct camera *cam)
{
    double dt = clamp_dt(dt_s);
    int turn = axis(st, INPUT_HOLD_TURN_LEFT, INPUT_HOLD_TURN_RIGHT);
    int pitch = axis(st, INPUT_HOLD_PITCH_UP, INPUT_HOLD_PITCH_DOWN);
    int move = axis(st, INPUT_HOLD_FORWARD, INPUT_HOLD_BACK);

    /* Move with the view the frame started with, then turn: one frame's order of operations
     * is invisible and this keeps each term separately testable. */
    if (move) {
        double alt = clamp_d(cam->pos[2], INPUT_ALT_MIN_M, INPUT_ALT_MAX_M);
        double dist = move * (INPUT_MOVE_BASE_MPS + INPUT_MOVE_PER_ALT_HZ * alt) * dt;
        double h = cam->heading_deg * (INPUT_PI / 180.0);
        double p = cam->pitch_deg * (INPUT_PI / 180.0);
        /* The view direction of camera.h: (cos p cos h, cos p sin h, sin p). */
        cam->pos[0] += dist * cos(p) * cos(h);
        cam->pos[1] += dist * cos(p) * sin(h);
        cam->pos[2] += dist * sin(p);
    }
    cam->pos[2] = clamp_d(cam->pos[2], INPUT_ALT_MIN_M, INPUT_ALT_MAX_M);

    double heading = fmod(cam->heading_deg + turn * INPUT_TURN_DEG_S * dt, 360.0);
    if (heading < 0.0)
        heading += 360.0;
    /* A heading just below 0 wraps to just below 360, which can round to 360.0f. */
    float heading_f = (float)heading;
    cam->heading_deg = heading_f >= 360.0f ? 0.0f : heading_f;
    cam->pitch_deg = (float)clamp_d(cam->pitch_deg + pitch * INPUT_PITCH_DEG_S * dt,
                                    -INPUT_PITCH_MAX_DEG, INPUT_PITCH_MAX_DEG);
}

float input_sun_step(const struct input_state *st, double dt_s, float sun_elev_deg)
{
    double e = sun_elev_deg + axis(st, INPUT_HOLD_SUN_UP, INPUT_HOLD_SUN_DOWN) *
                              INPUT_SUN_DEG_S * clamp_dt(dt_s);
    return (float)clamp_d(e, INPUT_SUN_MIN_DEG, INPUT_SUN_MAX_DEG);
}

/* ---- libinput ---------------------------------------------------------------------------- */

struct input {
    struct udev *udev;
    struct libinput *li;
    char seat[SEAT_MAX];
    int disabled;           /* desc.enable < 0 */
    int flush_tty;          /* flush stdin's typeahead at destroy */
    int dead;               /* libinput_dispatch failed for good: keep the fd, read no more */
    int keyboards;          /* attached devices with keys we bind */
    int open_failures;      /* device nodes open(2) refused */
    int last_open_errno;
    char last_open_path[128];
    char last_log[256];     /* libinput's last error message, newline removed */
    char why[384];          /* set when there is no usable context: what failed */
};

/* libinput opens every device node through us (no logind here: plain open(2) as this user). */
static int open_restricted(const char *path, int flags, void *user_data)
{
    struct input *in = user_data;
    int fd = open(path, flags | O_CLOEXEC);
    if (fd < 0) {
        int e = errno;
        in->open_failures++;
        in->last_open_errno = e;
        snprintf(in->last_open_path, sizeof in->last_open_path, "%s", path);
        return -e;
    }
    return fd;
}

static void close_restricted(int fd, void *user_data)
{
    (void)user_data;
    close(fd);
}

static const struct libinput_interface input_interface = {
    .open_restricted = open_restricted,
    .close_restricted = close_restricted,
};

/* Library code never prints: libinput's messages are kept for input_describe() instead. */
static void log_handler(struct libinput *li, enum libinput_log_priority priority,
                        const char *format, va_list args)
{
    (void)priority;
    struct input *in = libinput_get_user_data(li);
    if (!in)
        return;
    vsnprintf(in->last_log, sizeof in->last_log, format, args);
    size_t n = strlen(in->last_log);
    while (n > 0 && (in->last_log[n - 1] == '\n' || in->last_log[n - 1] == '\r'))
        in->last_log[--n] = '\0';
}

/* A power button or a lid switch is a "keyboard" to libinput too; count only devices that
 * can send the keys we bind, so input_active() means "the user can steer". */
static void device_added(struct input *in, struct libinput_device *dev)
{
    if (!libinput_device_has_capability(dev, LIBINPUT_DEVICE_CAP_KEYBOARD))
        return;
    if (libinput_device_keyboard_has_key(dev, KEY_ESC) != 1 &&
        libinput_device_keyboard_has_key(dev, KEY_W) != 1)
        return;
    /* The mark makes removal count exactly what was counted. */
    libinput_device_set_user_data(dev, in);
    in->keyboards++;
}

static void device_removed(struct input *in, struct libinput_device *dev)
{
    if (libinput_device_get_user_data(dev) == in && in->keyboards > 0) {
        libinput_device_set_user_data(dev, NULL);
        in->keyboards--;
    }
}

/* Drain every queued event; key events go into *st when given. Returns key events applied. */
static int drain(struct input *in, struct input_state *st)
{
    int keys = 0;
    struct libinput_event *ev;
    while ((ev = libinput_get_event(in->li)) != NULL) {
        switch (libinput_event_get_type(ev)) {
        case LIBINPUT_EVENT_DEVICE_ADDED:
            device_added(in, libinput_event_get_device(ev));
            break;
        case LIBINPUT_EVENT_DEVICE_REMOVED:
            device_removed(in, libinput_event_get_device(ev));
            break;
        case LIBINPUT_EVENT_KEYBOARD_KEY: {
            struct libinput_event_keyboard *k = libinput_event_get_keyboard_event(ev);
            int pressed = libinput_event_keyboard_get_key_state(k) == LIBINPUT_KEY_STATE_PRESSED;
            uint32_t count = libinput_event_keyboard_get_seat_key_count(k);
            /* The same key held on two keyboards: act on the seat's first press and last
             * release only, so the held bit does not drop while one is still down. */
            if (st && ((pressed && count == 1) || (!pressed && count == 0))) {
                input_apply_key(st, libinput_event_keyboard_get_key(k), pressed);
                keys++;
            }
            break;
        }
        default:
            break;
        }
        libinput_event_destroy(ev);
    }
    return keys;
}

int input_create(const struct input_desc *d, struct input **out, struct swell_err *err)
{
    if (!out)
        return swell_fail(err, SWELL_E_ARG, "input_create: out is NULL (a caller bug)");
    *out = NULL;
    struct input_desc desc = { 0 };
    if (d)
        desc = *d;
    const char *seat = desc.seat && desc.seat[0] ? desc.seat : DEFAULT_SEAT;
    if (strlen(seat) >= SEAT_MAX)
        return swell_fail(err, SWELL_E_ARG, "input: seat name '%.64s...' is too long (at most "
                          "%d characters)", seat, SEAT_MAX - 1);

    struct input *in = calloc(1, sizeof(*in));
    if (!in)
        return swell_fail(err, SWELL_E_NOMEM, "input: no memory for the input state");
    snprintf(in->seat, sizeof in->seat, "%s", seat);
    *out = in;
    in->flush_tty = desc.flush_tty >= 0;
    if (desc.enable < 0) {
        in->disabled = 1;
        return SWELL_OK;
    }

    /* From here on a failure leaves `in` inactive with the reason, never fails the call. */
    in->udev = udev_new();
    if (!in->udev) {
        snprintf(in->why, sizeof in->why, "udev_new failed: %s", strerror(errno));
        return SWELL_OK;
    }
    in->li = libinput_udev_create_context(&input_interface, in, in->udev);
    if (!in->li) {
        snprintf(in->why, sizeof in->why, "libinput_udev_create_context failed");
        goto fail_udev;
    }
    libinput_log_set_handler(in->li, log_handler);
    libinput_log_set_priority(in->li, LIBINPUT_LOG_PRIORITY_ERROR);
    if (libinput_udev_assign_seat(in->li, in->seat) != 0) {
        snprintf(in->why, sizeof in->why, "libinput could not take seat %s%s%s", in->seat,
                 in->last_log[0] ? ": " : "", in->last_log);
        goto fail_libinput;
    }
    /* The devices of the seat arrive as DEVICE_ADDED events queued by assign_seat. */
    if (libinput_dispatch(in->li) == 0)
        drain(in, NULL);
    return SWELL_OK;

fail_libinput:
    libinput_unref(in->li);
    in->li = NULL;
fail_udev:
    udev_unref(in->udev);
    in->udev = NULL;
    return SWELL_OK;
}

int input_poll(struct input *in, struct input_state *st)
{
    if (!st)
        return 0;
    input_clear_edges(st);
    if (!in || !in->li || in->dead)
        return 0;
    int r = libinput_dispatch(in->li);
    if (r < 0 && r != -EINTR && r != -EAGAIN) {
        in->dead = 1;
        snprintf(in->why, sizeof in->why, "libinput_dispatch failed: %s", strerror(-r));
        return 0;
    }
    return drain(in, st);
}

int input_active(const struct input *in)
{
    return in && in->li && !in->dead && in->keyboards > 0;
}

int input_keyboards(const struct input *in)
{
    return in && in->li && !in->dead ? in->keyboards : 0;
}

int input_fd(const struct input *in)
{
    return in && in->li && !in->dead ? libinput_get_fd(in->li) : -1;
}

void input_describe(const struct input *in, char *buf, size_t size)
{
    if (!buf || size == 0)
        return;
    if (!in) {
        snprintf(buf, size, "input: none");
    } else if (in->disabled) {
        snprintf(buf, size, "input: off");
    } else if (!in->li || in->dead) {
        snprintf(buf, size, "input: inactive (%s; keys are not read, quit with Ctrl-C)",
                 in->why);
    } else if (in->keyboards > 0) {
        snprintf(buf, size, "input: %d keyboard%s on %s", in->keyboards,
                 in->keyboards == 1 ? "" : "s", in->seat);
    } else if (in->open_failures > 0) {
        snprintf(buf, size, "input: inactive (no keyboard on %s: %d device%s could not be "
                 "opened, last %s: %s; run as root or add the user to the 'input' group)",
                 in->seat, in->open_failures, in->open_failures == 1 ? "" : "s",
                 in->last_open_path, strerror(in->last_open_errno));
    } else if (access("/dev/input", F_OK) != 0) {
        snprintf(buf, size, "input: inactive (no keyboard on %s: there is no /dev/input; "
                 "a keyboard plugged in later is picked up)", in->seat);
    } else {
        snprintf(buf, size, "input: inactive (no keyboard on %s: libinput takes only devices "
                 "udev has tagged, so udevd must be running; a keyboard plugged in later is "
                 "picked up)", in->seat);
    }
}

void input_destroy(struct input *in)
{
    if (!in)
        return;
    /* Only when keys were ours to read: without a context the terminal was the keyboard. */
    if (in->li && in->flush_tty && isatty(STDIN_FILENO))
        tcflush(STDIN_FILENO, TCIFLUSH);
    if (in->li)
        libinput_unref(in->li);
    if (in->udev)
        udev_unref(in->udev);
    free(in);
}
