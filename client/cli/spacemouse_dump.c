/* spacemouse_dump.c — `fluidcast spacemouse --dump`: prints every event of the
 * SpaceMouse service, one line each, until SIGINT, --count reports or (with
 * --exit-on-unplug) the device leaving. */
#include "spacemouse_dump.h"

#include <signal.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>

#include "cli_args.h"
#include "cli_report.h"
#include "cli_values.h"
#include "fc_error.h"
#include "spacemouse.h"

/* How often the wait for events looks for a pending SIGINT. */
#define POLL_MS 100

typedef struct dump_options {
    bool help;
    bool dump;
    bool exit_on_unplug;
    uint32_t count;               /* 0: until SIGINT */
} dump_options;

static fc_code set_dump(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name, (void)value, (void)err;
    ((dump_options *)o)->dump = true;
    return FC_OK;
}

static fc_code set_exit_on_unplug(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name, (void)value, (void)err;
    ((dump_options *)o)->exit_on_unplug = true;
    return FC_OK;
}

static fc_code set_count(void *o, const char *name, const char *value, fc_error *err)
{
    return fc_cli_parse_uint(name, value, 1, UINT32_MAX, &((dump_options *)o)->count, err);
}

static const fc_cli_option options[] = {
    {"--dump", false, set_dump},
    {"--count", true, set_count},
    {"--exit-on-unplug", false, set_exit_on_unplug},
};

static const fc_cli_command command = {"spacemouse", options, sizeof options / sizeof options[0], NULL};

static void print_help(FILE *to)
{
    fputs("usage: fluidcast spacemouse --dump [--count N] [--exit-on-unplug]\n"
          "\n"
          "Reads a 3Dconnexion SpaceMouse directly over USB (libusb; no spacenavd) and\n"
          "prints each report: its raw bytes, what it decoded to (axes as sent and\n"
          "normalised to [-1, 1], buttons held, pressed and released), and the device\n"
          "arriving and leaving. Plug it in or out at any time. Ends on Ctrl-C.\n"
          "Without permission to open the device it says so: install\n"
          "deploy/udev/70-fluidcast-spacemouse.rules (see docs/viewer.md).\n"
          "\n"
          "options:\n"
          "  --dump                  print the reports (required)\n"
          "  --count N               exit after N reports\n"
          "  --exit-on-unplug        exit when the device leaves\n"
          "  -h, --help              show this help\n"
          "\n",
          to);
    fc_cli_print_exit_codes(to);
}

static void print_device(const char *what, const fc_sm_event *ev)
{
    printf("%s: %s %04x:%04x bus %u device %u%s%s%s\n", what, ev->name, ev->vendor, ev->product, ev->bus,
           ev->address, ev->message[0] ? " (" : "", ev->message, ev->message[0] ? ")" : "");
}

static void print_report(uint32_t number, const fc_sm_event *ev)
{
    const fc_sm_state *s = &ev->state;
    printf("report %u: %zu bytes", number, ev->length);
    for (size_t i = 0; i < ev->length; i++)
        printf(" %02x", ev->report[i]);
    printf(" | %s | raw %d %d %d %d %d %d | axes %+.3f %+.3f %+.3f %+.3f %+.3f %+.3f"
           " | buttons 0x%x pressed 0x%x released 0x%x",
           fc_sm_report_kind_name(ev->kind), s->raw[0], s->raw[1], s->raw[2], s->raw[3], s->raw[4],
           s->raw[5], (double)s->axes[0], (double)s->axes[1], (double)s->axes[2], (double)s->axes[3],
           (double)s->axes[4], (double)s->axes[5], s->buttons, s->pressed, s->released);
    if (s->long_presses)
        printf(" | long-press 0x%x", s->long_presses);
    if (s->battery_percent >= 0)
        printf(" | battery %d%%", s->battery_percent);
    if (ev->dropped)
        printf(" | %u events dropped before", ev->dropped);
    printf("\n");
}

/* True when the run is over. */
static bool print_event(const dump_options *o, const fc_sm_event *ev, uint32_t *reports)
{
    switch (ev->type) {
    case FC_SM_EVENT_ARRIVED:
        print_device("arrived", ev);
        break;
    case FC_SM_EVENT_LEFT:
        print_device("left", ev);
        return o->exit_on_unplug;
    case FC_SM_EVENT_NOTICE:
        fprintf(stderr, "fluidcast: spacemouse: %s; carrying on without it\n", ev->message);
        break;
    case FC_SM_EVENT_REPORT:
        print_report(++*reports, ev);
        return o->count != 0 && *reports >= o->count;
    }
    return false;
}

static bool interrupted(void)
{
    sigset_t pending;
    return sigpending(&pending) == 0 && sigismember(&pending, SIGINT);
}

static int dump(const dump_options *o)
{
    /* SIGINT stays blocked (in the event thread too, which inherits the mask)
     * and is polled: no handler, no global flag. */
    sigset_t block;
    sigemptyset(&block);
    sigaddset(&block, SIGINT);
    pthread_sigmask(SIG_BLOCK, &block, NULL);
    fc_spacemouse_options sm_options;
    fc_spacemouse_options_default(&sm_options);
    fc_spacemouse *sm;
    fc_error err;
    if (fc_spacemouse_start(&sm_options, &sm, &err) != FC_OK)
        return fc_cli_fail(FC_EXIT_INPUT, "spacemouse: %s", err.message);
    fprintf(stderr, "fluidcast: watching for a SpaceMouse (Ctrl-C to stop)\n");
    uint32_t reports = 0;
    bool done = false;
    while (!done && !interrupted()) {
        fc_sm_event ev;
        if (fc_spacemouse_next(sm, &ev, POLL_MS))
            done = print_event(o, &ev, &reports);
        fflush(stdout);
    }
    fc_spacemouse_stop(sm);
    return FC_EXIT_OK;
}

int fc_spacemouse_main(int argc, char **argv)
{
    dump_options o;
    memset(&o, 0, sizeof o);
    fc_error err;
    if (fc_cli_parse_args(&command, argc, argv, &o, &o.help, &err) != FC_OK)
        return fc_cli_fail(FC_EXIT_USAGE, "%s", err.message);
    if (o.help) {
        print_help(stdout);
        return FC_EXIT_OK;
    }
    if (!o.dump)
        return fc_cli_fail(FC_EXIT_USAGE, "spacemouse needs --dump (see fluidcast spacemouse --help)");
    return dump(&o);
}
