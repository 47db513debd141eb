/* test_input.c - keyboard input without a keyboard: the bindings of issue 4 (written out here
 * from the issue with linux/input-event-codes.h, not read from input.c) pressed and released,
 * one-shot flags and their clearing, every other key code ignored; the camera step against
 * the view-direction formula of camera.h and against the exact solution of the nose-down
 * descent ODE; the sun step; and the libinput context in a place with no input devices
 * (create succeeds, inactive, polls nothing, destroys cleanly). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include <cmocka.h>
#include <linux/input-event-codes.h>

#include "platform/input.h"

#define PI 3.14159265358979323846

/* cmocka 1.1.5 has no double comparison; this one prints both values when it fails. */
#define assert_near(a, b, tol) \
    near_impl((double)(a), (double)(b), (double)(tol), #a, __FILE__, __LINE__)

static void near_impl(double a, double b, double tol, const char *what, const char *file,
                      int line)
{
    if (!(fabs(a - b) <= tol)) {
        print_error("%s = %.17g, expected %.17g (tolerance %g)\n", what, a, b, tol);
        _fail(file, line);
    }
}

/* Issue 4's held bindings: key, action. */
static const struct { uint32_t key; int hold; } held_keys[] = {
    { KEY_W, INPUT_HOLD_FORWARD },       { KEY_UP, INPUT_HOLD_FORWARD },
    { KEY_S, INPUT_HOLD_BACK },          { KEY_DOWN, INPUT_HOLD_BACK },
    { KEY_A, INPUT_HOLD_TURN_LEFT },     { KEY_LEFT, INPUT_HOLD_TURN_LEFT },
    { KEY_D, INPUT_HOLD_TURN_RIGHT },    { KEY_RIGHT, INPUT_HOLD_TURN_RIGHT },
    { KEY_PAGEUP, INPUT_HOLD_PITCH_UP }, { KEY_PAGEDOWN, INPUT_HOLD_PITCH_DOWN },
    { KEY_RIGHTBRACE, INPUT_HOLD_SUN_UP }, { KEY_LEFTBRACE, INPUT_HOLD_SUN_DOWN },
};
#define N_HELD (sizeof held_keys / sizeof held_keys[0])

static const uint32_t quit_keys[] = { KEY_ESC, KEY_Q };
static const uint32_t shot_keys[] = { KEY_F12, KEY_P };
static const struct { uint32_t key; int preset; const char *name; } preset_keys[] = {
    { KEY_1, INPUT_PRESET_CALM, "calm" },   { KEY_2, INPUT_PRESET_MODERATE, "moderate" },
    { KEY_3, INPUT_PRESET_ROUGH, "rough" }, { KEY_4, INPUT_PRESET_STORM, "storm" },
};

static int is_bound(uint32_t key)
{
    for (size_t i = 0; i < N_HELD; i++)
        if (held_keys[i].key == key)
            return 1;
    for (size_t i = 0; i < 2; i++)
        if (quit_keys[i] == key || shot_keys[i] == key)
            return 1;
    for (size_t i = 0; i < 4; i++)
        if (preset_keys[i].key == key)
            return 1;
    return key == KEY_B;   /* the demo boat */
}

static int any_held(const struct input_state *st)
{
    for (int h = 0; h < INPUT_HOLD_COUNT; h++)
        if (input_held(st, h))
            return 1;
    return 0;
}

static void assert_idle(const struct input_state *st)
{
    assert_false(any_held(st));
    assert_int_equal(st->quit, 0);
    assert_int_equal(st->screenshot, 0);
    assert_int_equal(st->boat, 0);
    assert_int_equal(st->preset, INPUT_PRESET_NONE);
}

static void test_held_keys(void **unused)
{
    (void)unused;
    struct input_state st;
    for (size_t i = 0; i < N_HELD; i++) {
        input_state_init(&st);
        input_apply_key(&st, held_keys[i].key, 1);
        for (int h = 0; h < INPUT_HOLD_COUNT; h++)
            assert_int_equal(input_held(&st, h), h == held_keys[i].hold);
        assert_int_equal(st.quit, 0);
        assert_int_equal(st.screenshot, 0);
        assert_int_equal(st.preset, INPUT_PRESET_NONE);
        /* Autorepeat changes nothing; a poll-like clear keeps held keys. */
        input_apply_key(&st, held_keys[i].key, 2);
        input_clear_edges(&st);
        assert_true(input_held(&st, held_keys[i].hold));
        input_apply_key(&st, held_keys[i].key, 0);
        assert_idle(&st);
    }
    /* Two keys of one action, in either release order: releasing one keeps it going. */
    for (size_t i = 0; i < N_HELD; i++) {
        for (size_t j = 0; j < N_HELD; j++) {
            if (i == j || held_keys[i].hold != held_keys[j].hold)
                continue;
            input_state_init(&st);
            input_apply_key(&st, held_keys[i].key, 1);
            input_apply_key(&st, held_keys[j].key, 1);
            input_apply_key(&st, held_keys[i].key, 0);
            assert_true(input_held(&st, held_keys[i].hold));
            input_apply_key(&st, held_keys[j].key, 0);
            assert_idle(&st);
        }
    }
    /* A release without a press (key down before start) is harmless. */
    input_apply_key(&st, KEY_S, 0);
    assert_idle(&st);
    assert_false(input_held(&st, -1));
    assert_false(input_held(&st, INPUT_HOLD_COUNT));
}

static void test_one_shots(void **unused)
{
    (void)unused;
    struct input_state st;
    for (size_t i = 0; i < 2; i++) {
        input_state_init(&st);
        input_apply_key(&st, shot_keys[i], 0);
        assert_int_equal(st.screenshot, 0);     /* a release is no request */
        input_apply_key(&st, shot_keys[i], 1);
        assert_int_equal(st.screenshot, 1);
        input_apply_key(&st, shot_keys[i], 0);
        assert_int_equal(st.screenshot, 1);     /* stays until cleared */
        input_clear_edges(&st);
        assert_idle(&st);
        input_apply_key(&st, shot_keys[i], 2);  /* autorepeat: no second screenshot */
        assert_int_equal(st.screenshot, 0);
    }
    /* B shows or hides the demo boat, once per press */
    input_state_init(&st);
    input_apply_key(&st, KEY_B, 1);
    assert_int_equal(st.boat, 1);
    input_apply_key(&st, KEY_B, 0);
    assert_int_equal(st.boat, 1);
    input_clear_edges(&st);
    assert_idle(&st);
    input_apply_key(&st, KEY_B, 2);
    assert_int_equal(st.boat, 0);
    for (size_t i = 0; i < 4; i++) {
        input_state_init(&st);
        input_apply_key(&st, preset_keys[i].key, 1);
        assert_int_equal(st.preset, preset_keys[i].preset);
        assert_string_equal(input_preset_name(st.preset), preset_keys[i].name);
        input_apply_key(&st, preset_keys[i].key, 0);
        assert_int_equal(st.preset, preset_keys[i].preset);
        input_clear_edges(&st);
        assert_idle(&st);
    }
    /* Two presets in one poll: the last wins. */
    input_state_init(&st);
    input_apply_key(&st, KEY_4, 1);
    input_apply_key(&st, KEY_2, 1);
    assert_int_equal(st.preset, INPUT_PRESET_MODERATE);
    assert_string_equal(input_preset_name(INPUT_PRESET_NONE), "none");
    assert_string_equal(input_preset_name(INPUT_PRESET_COUNT), "none");
    /* Quit is sticky: no clear forgets it. */
    for (size_t i = 0; i < 2; i++) {
        input_state_init(&st);
        input_apply_key(&st, quit_keys[i], 1);
        input_apply_key(&st, quit_keys[i], 0);
        input_clear_edges(&st);
        assert_int_equal(st.quit, 1);
        assert_false(any_held(&st));
    }
}

static void test_unknown_keys_ignored(void **unused)
{
    (void)unused;
    struct input_state st;
    input_state_init(&st);
    for (uint32_t k = 0; k <= KEY_MAX + 16u; k++) {
        if (is_bound(k))
            continue;
        input_apply_key(&st, k, 1);
        input_apply_key(&st, k, 2);
        assert_idle(&st);
    }
    /* Nor do they release a held key. */
    input_apply_key(&st, KEY_D, 1);
    for (uint32_t k = 0; k <= KEY_MAX; k++)
        if (!is_bound(k))
            input_apply_key(&st, k, 0);
    assert_true(input_held(&st, INPUT_HOLD_TURN_RIGHT));
    input_apply_key(&st, 0xffffffffu, 1);
    assert_true(input_held(&st, INPUT_HOLD_TURN_RIGHT));
}

static struct camera level_camera(double alt, float heading)
{
    struct camera c;
    camera_defaults(&c);
    c.pos[0] = 100.0;
    c.pos[1] = -50.0;
    c.pos[2] = alt;
    c.heading_deg = heading;
    c.pitch_deg = 0.0f;
    return c;
}

static void test_camera_move(void **unused)
{
    (void)unused;
    struct input_state st;
    input_state_init(&st);
    const double dt = 0.1;
    const float headings[] = { 0.0f, 30.0f, 90.0f, 200.0f, 359.0f };
    const double alts[] = { 2.0, 100.0, 10000.0 };
    for (size_t a = 0; a < 3; a++) {
        for (size_t i = 0; i < 5; i++) {
            double v = INPUT_MOVE_BASE_MPS + INPUT_MOVE_PER_ALT_HZ * alts[a];
            double h = headings[i] * PI / 180.0;
            for (int dir = 1; dir >= -1; dir -= 2) {
                input_state_init(&st);
                input_apply_key(&st, dir > 0 ? KEY_UP : KEY_S, 1);
                struct camera c = level_camera(alts[a], headings[i]);
                input_camera_step(&st, dt, &c);
                double tol = 1e-9 * (1.0 + v);
                assert_near(c.pos[0], 100.0 + dir * v * dt * cos(h), tol);
                assert_near(c.pos[1], -50.0 + dir * v * dt * sin(h), tol);
                assert_near(c.pos[2], alts[a], 1e-9);
                assert_true(c.heading_deg == headings[i]);
                assert_true(c.pitch_deg == 0.0f);
            }
        }
    }
    /* Forward and back together, or nothing held: the camera stays. */
    struct camera c = level_camera(10.0, 45.0f);
    input_state_init(&st);
    input_camera_step(&st, dt, &c);
    input_apply_key(&st, KEY_W, 1);
    input_apply_key(&st, KEY_DOWN, 1);
    input_camera_step(&st, dt, &c);
    assert_true(c.pos[0] == 100.0 && c.pos[1] == -50.0 && c.pos[2] == 10.0);
    /* Pitched up 30 degrees, the climb is v dt sin 30 and the ground track v dt cos 30. */
    input_state_init(&st);
    input_apply_key(&st, KEY_W, 1);
    c = level_camera(100.0, 0.0f);
    c.pitch_deg = 30.0f;
    input_camera_step(&st, dt, &c);
    double v = INPUT_MOVE_BASE_MPS + INPUT_MOVE_PER_ALT_HZ * 100.0;
    assert_near(c.pos[2], 100.0 + v * dt * 0.5, 1e-6);
    assert_near(c.pos[0], 100.0 + v * dt * sqrt(3.0) / 2.0, 1e-6);
    assert_near(c.pos[1], -50.0, 1e-9);
}

static void test_camera_turn_pitch(void **unused)
{
    (void)unused;
    struct input_state st;
    const double dt = 0.1;
    const uint32_t left[2] = { KEY_A, KEY_LEFT }, right[2] = { KEY_D, KEY_RIGHT };
    for (int i = 0; i < 2; i++) {
        input_state_init(&st);
        input_apply_key(&st, left[i], 1);
        struct camera c = level_camera(10.0, 90.0f);
        input_camera_step(&st, dt, &c);
        /* Left is counter-clockwise seen from above: heading increases. */
        assert_near(c.heading_deg, 90.0 + INPUT_TURN_DEG_S * dt, 1e-4);
        assert_true(c.pos[0] == 100.0 && c.pos[1] == -50.0 && c.pos[2] == 10.0);
        input_state_init(&st);
        input_apply_key(&st, right[i], 1);
        c = level_camera(10.0, 90.0f);
        input_camera_step(&st, dt, &c);
        assert_near(c.heading_deg, 90.0 - INPUT_TURN_DEG_S * dt, 1e-4);
    }
    /* Wrapping into [0, 360). */
    input_state_init(&st);
    input_apply_key(&st, KEY_D, 1);
    struct camera c = level_camera(10.0, 1.0f);
    input_camera_step(&st, dt, &c);
    assert_near(c.heading_deg, 361.0 - INPUT_TURN_DEG_S * dt, 1e-3);
    input_state_init(&st);
    input_apply_key(&st, KEY_A, 1);
    c = level_camera(10.0, 359.0f);
    input_camera_step(&st, dt, &c);
    assert_near(c.heading_deg, INPUT_TURN_DEG_S * dt - 1.0, 1e-3);
    for (int k = 0; k < 1000; k++) {
        input_camera_step(&st, 0.0173, &c);
        assert_true(c.heading_deg >= 0.0f && c.heading_deg < 360.0f);
    }
    /* Pitch: rate, then the clamp at +-89. */
    input_state_init(&st);
    input_apply_key(&st, KEY_PAGEUP, 1);
    c = level_camera(10.0, 0.0f);
    input_camera_step(&st, dt, &c);
    assert_near(c.pitch_deg, INPUT_PITCH_DEG_S * dt, 1e-4);
    for (int k = 0; k < 100; k++)
        input_camera_step(&st, 0.2, &c);
    assert_near(c.pitch_deg, INPUT_PITCH_MAX_DEG, 1e-6);
    input_state_init(&st);
    input_apply_key(&st, KEY_PAGEDOWN, 1);
    for (int k = 0; k < 100; k++)
        input_camera_step(&st, 0.2, &c);
    assert_near(c.pitch_deg, -INPUT_PITCH_MAX_DEG, 1e-6);
}

/* Flying nose-down at pitch p obeys dz/dt = -(a + b z) sin|p| (a, b the documented speed
 * law), solved exactly by z(t) = (z0 + a/b) exp(-b sin|p| t) - a/b. Small steps must follow
 * it; long runs and huge steps must never reach the sea. */
static void test_camera_altitude(void **unused)
{
    (void)unused;
    struct input_state st;
    input_state_init(&st);
    input_apply_key(&st, KEY_W, 1);
    const double a = INPUT_MOVE_BASE_MPS, b = INPUT_MOVE_PER_ALT_HZ;
    struct camera c = level_camera(1000.0, 10.0f);
    c.pitch_deg = -20.0f;
    double s = sin(20.0 * PI / 180.0);
    const int steps = 20000;
    const double t = 2.0;
    for (int k = 0; k < steps; k++)
        input_camera_step(&st, t / steps, &c);
    double z = (1000.0 + a / b) * exp(-b * s * t) - a / b;
    assert_near(c.pos[2], z, 1e-3 * z);

    c = level_camera(5.0, 0.0f);
    c.pitch_deg = -89.0f;
    for (int k = 0; k < 1000; k++) {
        input_camera_step(&st, 0.25, &c);
        assert_true(c.pos[2] >= INPUT_ALT_MIN_M && c.pos[2] > 0.0);
    }
    /* A stalled frame is integrated as INPUT_DT_MAX_S, not as the whole stall; a negative or
     * NaN dt moves nothing. */
    struct camera c1 = level_camera(50.0, 0.0f), c2 = c1, c3 = c1;
    input_state_init(&st);
    input_apply_key(&st, KEY_W, 1);
    input_camera_step(&st, 30.0, &c1);
    input_camera_step(&st, INPUT_DT_MAX_S, &c2);
    assert_true(c1.pos[0] == c2.pos[0]);
    input_camera_step(&st, -1.0, &c3);
    input_camera_step(&st, NAN, &c3);
    assert_true(c3.pos[0] == 100.0);
    /* Climbing stops at the ceiling. */
    c = level_camera(40000.0, 0.0f);
    c.pitch_deg = 89.0f;
    for (int k = 0; k < 100; k++)
        input_camera_step(&st, 0.25, &c);
    assert_near(c.pos[2], INPUT_ALT_MAX_M, 1e-9);
}

static void test_sun_step(void **unused)
{
    (void)unused;
    struct input_state st;
    input_state_init(&st);
    assert_near(input_sun_step(&st, 0.1, 30.0f), 30.0f, 0.0);
    input_apply_key(&st, KEY_RIGHTBRACE, 1);
    assert_near(input_sun_step(&st, 0.1, 30.0f), 30.0 + INPUT_SUN_DEG_S * 0.1, 1e-4);
    assert_near(input_sun_step(&st, 0.25, 89.9f), INPUT_SUN_MAX_DEG, 0.0);
    input_apply_key(&st, KEY_RIGHTBRACE, 0);
    input_apply_key(&st, KEY_LEFTBRACE, 1);
    assert_near(input_sun_step(&st, 0.1, 30.0f), 30.0 - INPUT_SUN_DEG_S * 0.1, 1e-4);
    float e = 30.0f;
    for (int k = 0; k < 100; k++)
        e = input_sun_step(&st, 0.25, e);
    assert_near(e, INPUT_SUN_MIN_DEG, 0.0);
    assert_true(e > 0.0f);      /* 0 would mean "default" to the renderer */
}

/* This container has no /dev/input: create must still succeed, inactive. Where devices do
 * exist (a developer's machine) only the consistency of the reports is checked. */
static void test_device_none(void **unused)
{
    (void)unused;
    struct swell_err err = { 0 };
    struct input *in = NULL;
    struct input_desc d = { 0 };
    assert_int_equal(input_create(&d, &in, &err), SWELL_OK);
    assert_non_null(in);
    char desc[512];
    input_describe(in, desc, sizeof desc);
    assert_non_null(strstr(desc, "input: "));
    int no_devices = access("/dev/input", F_OK) != 0;
    if (no_devices) {
        assert_int_equal(input_active(in), 0);
        assert_int_equal(input_keyboards(in), 0);
        assert_non_null(strstr(desc, "inactive"));
    }
    assert_int_equal(input_active(in), input_keyboards(in) > 0);

    struct input_state st;
    input_state_init(&st);
    input_apply_key(&st, KEY_W, 1);
    input_apply_key(&st, KEY_F12, 1);
    input_apply_key(&st, KEY_3, 1);
    for (int k = 0; k < 3; k++) {
        int n = input_poll(in, &st);
        assert_true(n >= 0);
        if (no_devices) {
            assert_int_equal(n, 0);
            /* The poll cleared the edges and kept the held key. */
            assert_int_equal(st.screenshot, 0);
            assert_int_equal(st.preset, INPUT_PRESET_NONE);
            assert_int_equal(st.quit, 0);
            assert_true(input_held(&st, INPUT_HOLD_FORWARD));
        }
    }
    input_destroy(in);

    /* Disabled: no context, no fd. */
    in = NULL;
    d.enable = -1;
    assert_int_equal(input_create(&d, &in, &err), SWELL_OK);
    assert_int_equal(input_active(in), 0);
    assert_int_equal(input_fd(in), -1);
    assert_int_equal(input_poll(in, &st), 0);
    input_describe(in, desc, sizeof desc);
    assert_string_equal(desc, "input: off");
    input_destroy(in);

    /* NULL descriptor means defaults; NULL handle everywhere is harmless. */
    in = NULL;
    assert_int_equal(input_create(NULL, &in, &err), SWELL_OK);
    input_destroy(in);
    input_destroy(NULL);
    assert_int_equal(input_poll(NULL, &st), 0);
    assert_int_equal(input_fd(NULL), -1);
    assert_int_equal(input_active(NULL), 0);
    input_describe(NULL, desc, 8);
    assert_true(strlen(desc) < 8);

    /* Bad arguments are the only failures. */
    assert_int_equal(input_create(&d, NULL, &err), SWELL_E_ARG);
    char seat[200];
    memset(seat, 's', sizeof seat - 1);
    seat[sizeof seat - 1] = '\0';
    struct input_desc long_seat = { .seat = seat };
    in = (struct input *)&err;
    assert_int_equal(input_create(&long_seat, &in, &err), SWELL_E_ARG);
    assert_null(in);
    assert_non_null(strstr(err.msg, "seat"));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_held_keys),
        cmocka_unit_test(test_one_shots),
        cmocka_unit_test(test_unknown_keys_ignored),
        cmocka_unit_test(test_camera_move),
        cmocka_unit_test(test_camera_turn_pitch),
        cmocka_unit_test(test_camera_altitude),
        cmocka_unit_test(test_sun_step),
        cmocka_unit_test(test_device_none),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
