/* input.h - keyboard for the fullscreen KMS mode, through libinput (issue 4).
 *
 * Two halves. The device half (input_create / input_poll / input_destroy) opens libinput on a
 * udev seat and drains its events without blocking; it never stops the program: with no input
 * devices (no /dev/input, no permission, no udev) it is simply inactive and says why through
 * input_describe(). The action half is pure: input_apply_key() maps evdev KEY_* codes
 * (linux/input-event-codes.h) onto a small value-type struct input_state, and
 * input_camera_step() / input_sun_step() turn held actions into motion, so both are tested
 * without any device.
 *
 * Bindings are physical key positions (evdev codes, no keymap), so WASD stays under the left
 * hand on any layout:
 *   quit                    Esc, Q                 (sticky)
 *   forward / back          W, S  or  Up, Down     (held)
 *   turn left / right       A, D  or  Left, Right  (held; left = heading increases, CCW)
 *   pitch up / down         PageUp, PageDown       (held)
 *   sun elevation + / -     ]  /  [                (held)
 *   wind preset             1 calm, 2 moderate, 3 rough, 4 storm   (one-shot)
 *   screenshot              F12, P                 (one-shot)
 *   demo boat on / off      B                      (one-shot; swell --boat)
 * libinput sends no autorepeat, so held actions are booleans integrated over frame time.
 *
 * Camera conventions are camera.h's: x east, y north, z up, metres; heading CCW from +x;
 * pitch negative looking down; degrees.
 */
#ifndef SWELL_INPUT_H
#define SWELL_INPUT_H

#include <stddef.h>
#include <stdint.h>
#include "core/camera.h"
#include "core/err.h"

/* Movement along the view direction, m/s: base plus a multiple of the altitude, so the ground
 * sweeps past the view at a similar angular rate from 2 m (3 m/s) to 10 km (5 km/s). */
#define INPUT_MOVE_BASE_MPS 2.0
#define INPUT_MOVE_PER_ALT_HZ 0.5
#define INPUT_TURN_DEG_S 60.0       /* heading rate while turning */
#define INPUT_PITCH_DEG_S 30.0      /* pitch rate */
#define INPUT_SUN_DEG_S 10.0        /* sun elevation rate */
/* Limits kept by the steps: the swell CLI's ranges (--camera, --pitch, --sun). The sun stays
 * above 0 because the renderer reads an elevation of 0 as "default". */
#define INPUT_ALT_MIN_M 1.0
#define INPUT_ALT_MAX_M 500000.0
#define INPUT_PITCH_MAX_DEG 89.0
#define INPUT_SUN_MIN_DEG 1.0
#define INPUT_SUN_MAX_DEG 90.0
/* A longer frame (a stall, a VT switch) is integrated as this long, not as a jump. */
#define INPUT_DT_MAX_S 0.25

/* Actions that last while a key is held. */
enum input_hold {
    INPUT_HOLD_FORWARD = 0,
    INPUT_HOLD_BACK,
    INPUT_HOLD_TURN_LEFT,
    INPUT_HOLD_TURN_RIGHT,
    INPUT_HOLD_PITCH_UP,
    INPUT_HOLD_PITCH_DOWN,
    INPUT_HOLD_SUN_UP,
    INPUT_HOLD_SUN_DOWN,
    INPUT_HOLD_COUNT
};

/* Wind presets the number keys select; input_preset_name() gives the tables/<name>.preset. */
enum input_preset {
    INPUT_PRESET_NONE = -1,
    INPUT_PRESET_CALM = 0,
    INPUT_PRESET_MODERATE,
    INPUT_PRESET_ROUGH,
    INPUT_PRESET_STORM,
    INPUT_PRESET_COUNT
};

/* Value type: copy it, zero it with input_state_init(). */
struct input_state {
    /* Per action, one bit per binding currently down (W and Up are bits of FORWARD), so
     * releasing one of two held keys keeps the action going. Test with input_held(). */
    uint8_t held[INPUT_HOLD_COUNT];
    int quit;           /* sticky: Esc or Q was pressed */
    int screenshot;     /* one-shot: F12 or P pressed since the last input_clear_edges() */
    int boat;           /* one-shot: B pressed since then (the demo boat shown or hidden) */
    int preset;         /* one-shot: enum input_preset chosen since then (last wins), or NONE */
};

void input_state_init(struct input_state *st);
/* Forget the one-shot flags (screenshot, preset); held keys and quit stay. input_poll() calls
 * it first, so the flags it returns describe that poll only. */
void input_clear_edges(struct input_state *st);
/* pressed: 1 press, 0 release, 2 (evdev autorepeat) ignored. Unbound keys are ignored. */
void input_apply_key(struct input_state *st, uint32_t linux_keycode, int pressed);
int input_held(const struct input_state *st, int hold);     /* 1 while any binding is down */
const char *input_preset_name(int preset);                  /* "calm".."storm", or "none" */

/* Advance the camera by dt_s (clamped to [0, INPUT_DT_MAX_S]) of the held actions: forward
 * and back along the view direction (pitch included, so flying nose-down descends) at
 * INPUT_MOVE_BASE_MPS + INPUT_MOVE_PER_ALT_HZ * altitude; altitude, pitch kept in range,
 * heading wrapped into [0, 360). */
void input_camera_step(const struct input_state *st, double dt_s, struct camera *cam);
/* The sun elevation after dt_s of held ] / [, in [INPUT_SUN_MIN_DEG, INPUT_SUN_MAX_DEG]. */
float input_sun_step(const struct input_state *st, double dt_s, float sun_elev_deg);

struct input_desc {
    int enable;         /* 0 = default: on; 1 on; -1 off (create gives an inactive input at
                           once, touching no device: surfaceless runs, tests) */
    const char *seat;   /* udev seat to take devices from; default "seat0" */
    int flush_tty;      /* 0 = default: on; -1 off. The console keyboard also types into the
                           terminal swell was started from; destroy discards that typeahead
                           (tcflush of stdin when it is a terminal) so the keys steering the
                           camera do not run as shell commands after exit */
};

struct input;

/* Fails only on a bad argument or no memory. No devices is not an error: input_active() is 0
 * and input_describe() says why. Create after the platform opens. */
int  input_create(const struct input_desc *d, struct input **out, struct swell_err *err);
/* Non-blocking: dispatch libinput, drain its events into *st (edges cleared first). Returns
 * the number of key events applied (0 when inactive). A dead libinput context makes the input
 * inactive rather than failing the frame. */
int  input_poll(struct input *in, struct input_state *st);
int  input_active(const struct input *in);  /* 1 while a keyboard is attached (hotplug too) */
int  input_keyboards(const struct input *in);
/* libinput's fd to wait on with poll(2), or -1 without a libinput context. */
int  input_fd(const struct input *in);
/* One line: "input: 1 keyboard on seat0" or "input: inactive (why; what to do)". */
void input_describe(const struct input *in, char *buf, size_t size);
/* NULL and half-built accepted. Flushes the terminal's typeahead (input_desc.flush_tty). */
void input_destroy(struct input *in);

#endif
