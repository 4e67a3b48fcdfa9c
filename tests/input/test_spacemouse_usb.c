/* test_spacemouse_usb.c — the real libusb path of the SpaceMouse service,
 * run under umockdev-run with a scripted device (run_umockdev.sh): the device
 * is enumerated and claimed (ARRIVED), each scripted report arrives with the
 * decoded state expected after it, button edges turn into actions, the zero
 * report stops the motion, and the URB status -19 at the end of the script is
 * an unplug (LEFT, no NOTICE). Event times come from an injected clock, which
 * also drives the filter's watchdog.
 *
 * usage: test_spacemouse_usb compact|navigator */
#include <stdatomic.h>
#include <stdio.h>
#include <string.h>

#include "spacemouse.h"
#include "spacemouse_filter.h"
#include "spacemouse_motion.h"
#include "test_util.h"

#define MS 1000000ull
#define WAIT_MS 5000
#define MAX_REPORTS 8

typedef struct expected_report {
    fc_sm_report_kind kind;
    int16_t raw[6];
    uint32_t buttons, pressed, released;
} expected_report;

typedef struct device_script {
    const char *name;
    uint16_t vendor, product;
    size_t count;
    expected_report reports[MAX_REPORTS];
} device_script;

/* What compact.ioctl and navigator.ioctl send, report by report. */
static const device_script scripts[] = {
    {"compact", 0x256f, 0xc635, 6,
     {{FC_SM_REPORT_SIX_AXIS, {10, 20, 30, 40, 50, 60}, 0, 0, 0},
      {FC_SM_REPORT_SIX_AXIS, {350, -350, 400, -400, 175, -175}, 0, 0, 0},
      {FC_SM_REPORT_BUTTONS, {350, -350, 400, -400, 175, -175}, 1, 1, 0},
      {FC_SM_REPORT_BUTTONS, {350, -350, 400, -400, 175, -175}, 2, 2, 1},
      {FC_SM_REPORT_BUTTONS, {350, -350, 400, -400, 175, -175}, 0, 0, 2},
      {FC_SM_REPORT_SIX_AXIS, {0, 0, 0, 0, 0, 0}, 0, 0, 0}}},
    {"navigator", 0x046d, 0xc626, 7,
     {{FC_SM_REPORT_TRANSLATION, {10, 20, 30, 0, 0, 0}, 0, 0, 0},
      {FC_SM_REPORT_ROTATION, {10, 20, 30, -10, -20, -30}, 0, 0, 0},
      {FC_SM_REPORT_BUTTONS, {10, 20, 30, -10, -20, -30}, 1, 1, 0},
      {FC_SM_REPORT_BUTTONS, {10, 20, 30, -10, -20, -30}, 3, 2, 0},
      {FC_SM_REPORT_BUTTONS, {10, 20, 30, -10, -20, -30}, 0, 0, 3},
      {FC_SM_REPORT_TRANSLATION, {0, 0, 0, -10, -20, -30}, 0, 0, 0},
      {FC_SM_REPORT_ROTATION, {0, 0, 0, 0, 0, 0}, 0, 0, 0}}},
};

/* The injected clock: 10 ms further at every reading. */
typedef struct fake_clock {
    atomic_ullong now;
} fake_clock;

static uint64_t fake_now(void *ctx)
{
    return atomic_fetch_add(&((fake_clock *)ctx)->now, 10 * MS) + 10 * MS;
}

static void count_wake(void *ctx)
{
    atomic_fetch_add((atomic_int *)ctx, 1);
}

static bool next_event(fc_spacemouse *sm, fc_sm_event *ev)
{
    bool got = fc_spacemouse_next(sm, ev, WAIT_MS);
    CHECK_MSG(got, "no event within %d ms", WAIT_MS);
    if (got && ev->type == FC_SM_EVENT_NOTICE)
        fprintf(stderr, "notice: %s\n", ev->message);
    return got;
}

static void check_report(const fc_sm_event *ev, const expected_report *want, size_t index)
{
    CHECK_MSG(ev->type == FC_SM_EVENT_REPORT, "event %zu has type %d", index, ev->type);
    CHECK_MSG(ev->kind == want->kind, "report %zu is %s, expected %s", index, fc_sm_report_kind_name(ev->kind),
              fc_sm_report_kind_name(want->kind));
    for (int i = 0; i < FC_SM_AXES; i++) {
        CHECK_MSG(ev->state.raw[i] == want->raw[i], "report %zu axis %d: %d, expected %d", index, i,
                  ev->state.raw[i], want->raw[i]);
        float norm = (float)want->raw[i] / 350.0f;
        norm = norm > 1 ? 1 : norm < -1 ? -1 : norm;
        CHECK_NEAR(ev->state.axes[i], norm, 1e-6);
    }
    CHECK_MSG(ev->state.buttons == want->buttons && ev->state.pressed == want->pressed &&
                  ev->state.released == want->released,
              "report %zu buttons 0x%x/+0x%x/-0x%x, expected 0x%x/+0x%x/-0x%x", index, ev->state.buttons,
              ev->state.pressed, ev->state.released, want->buttons, want->pressed, want->released);
}

/* What a viewer does with the events: filter, watchdog, actions. */
typedef struct viewer_model {
    fc_sm_filter filter;
    int resets, toggles;
    uint64_t last_time;
} viewer_model;

static void feed_viewer(viewer_model *v, const fc_sm_event *ev)
{
    CHECK_MSG(ev->time_ns > v->last_time, "event times must increase (%llu after %llu)",
              (unsigned long long)ev->time_ns, (unsigned long long)v->last_time);
    v->last_time = ev->time_ns;
    if (fc_sm_report_is_motion(ev->kind))
        fc_sm_filter_motion(&v->filter, &ev->state, ev->time_ns);
    fc_sm_actions a = fc_sm_button_actions(&ev->state);
    v->resets += a.reset;
    v->toggles += a.toggle_mode;
    float out[FC_SM_AXES];
    fc_sm_filter_output(&v->filter, ev->time_ns, out);
    bool moving = false;
    for (int i = 0; i < FC_SM_AXES; i++)
        moving = moving || out[i] != 0.0f;
    bool any_raw = false;
    for (int i = 0; i < FC_SM_AXES; i++)
        any_raw = any_raw || ev->state.raw[i] != 0;
    /* reports come 10 ms apart on the fake clock: the watchdog holds */
    CHECK_MSG(moving == any_raw, "filter %s while the device reports %s", moving ? "moves" : "rests",
              any_raw ? "deflection" : "zero");
    fc_sm_filter_output(&v->filter, ev->time_ns + 201 * MS, out);
    CHECK(out[0] == 0.0f && out[5] == 0.0f);   /* silence past the watchdog: rest */
}

static int run(const device_script *script)
{
    fake_clock clock;
    atomic_init(&clock.now, 0);
    atomic_int wakes;
    atomic_init(&wakes, 0);
    fc_spacemouse_options options;
    fc_spacemouse_options_default(&options);
    options.clock = (fc_sm_clock){fake_now, &clock};
    options.wake = count_wake;
    options.wake_ctx = &wakes;
    fc_spacemouse *sm;
    fc_error err;
    if (fc_spacemouse_start(&options, &sm, &err) != FC_OK) {
        fprintf(stderr, "start: %s\n", err.message);
        return 1;
    }
    viewer_model viewer = {0};
    fc_sm_filter_config filter_config;
    fc_sm_filter_config_default(&filter_config);
    fc_sm_filter_init(&viewer.filter, &filter_config);

    fc_sm_event ev;
    int events = 0;
    if (next_event(sm, &ev)) {
        events++;
        CHECK_MSG(ev.type == FC_SM_EVENT_ARRIVED, "first event has type %d, expected ARRIVED", ev.type);
        CHECK(ev.vendor == script->vendor && ev.product == script->product);
        CHECK(ev.bus == 1 && ev.address == 5);
        printf("arrived: %s %04x:%04x\n", ev.name, ev.vendor, ev.product);
    }
    for (size_t i = 0; i < script->count && next_event(sm, &ev); i++) {
        events++;
        check_report(&ev, &script->reports[i], i + 1);
        feed_viewer(&viewer, &ev);
        CHECK(ev.dropped == 0);
    }
    CHECK_MSG(viewer.resets == 1 && viewer.toggles == 1, "resets %d toggles %d, expected one each",
              viewer.resets, viewer.toggles);
    if (next_event(sm, &ev)) {
        events++;
        CHECK_MSG(ev.type == FC_SM_EVENT_LEFT, "after the script: type %d, expected LEFT", ev.type);
        CHECK_MSG(strcmp(ev.message, "unplugged") == 0, "left because \"%s\"", ev.message);
        printf("left: %s\n", ev.message);
    }
    /* nothing after the unplug: no resubmission, no error */
    CHECK(!fc_spacemouse_next(sm, &ev, 300));
    fc_spacemouse_stop(sm);
    CHECK_MSG(atomic_load(&wakes) == events, "%d wake-ups for %d events", atomic_load(&wakes), events);
    return test_result();
}

int main(int argc, char **argv)
{
    for (size_t i = 0; argc == 2 && i < sizeof scripts / sizeof scripts[0]; i++)
        if (strcmp(argv[1], scripts[i].name) == 0)
            return run(&scripts[i]);
    fprintf(stderr, "usage: test_spacemouse_usb compact|navigator\n");
    return 2;
}
