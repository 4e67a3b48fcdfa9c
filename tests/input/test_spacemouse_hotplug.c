/* test_spacemouse_hotplug.c — hotplug of the SpaceMouse service through
 * libumockdev (run under umockdev-wrapper): started with no device, a Compact
 * plugged in arrives and streams its held report; its removal (uevent
 * "remove") is a LEFT, not an error; a SpaceNavigator plugged in afterwards
 * arrives, reports and leaves by URB status -19; a third device plugged in is
 * still streaming when the service stops, which must cancel its transfer and
 * return. Last, a device that cannot be used is a NOTICE, and the service
 * carries on: the next device plugged in is used.
 *
 * usage: test_spacemouse_hotplug DIR   (the folder of the device and ioctl scripts) */
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <umockdev.h>

#include "spacemouse.h"
#include "test_util.h"

#define DEVICE_SYSFS "/sys/devices/pci0000:00/0000:00:14.0/usb1/1-1"
#define INTERFACE_SYSFS DEVICE_SYSFS "/1-1:1.0"
#define HUB_SYSFS "/sys/devices/pci0000:00/0000:00:14.0/usb1"
#define WAIT_MS 5000
#define SKIP 77

/* The next event that is not a report; *reports counts those passed over. */
static bool next_non_report(fc_spacemouse *sm, fc_sm_event *ev, int *reports)
{
    while (fc_spacemouse_next(sm, ev, WAIT_MS)) {
        if (ev->type != FC_SM_EVENT_REPORT)
            return true;
        if (reports)
            ++*reports;
    }
    return false;
}

/* A device file of this folder (written for bus 1 device 5) as device
 * `devnum`: each plug gets a fresh node, since an ioctl handler stays bound to
 * its node for the testbed's life. */
static gchar *device_text(const char *dir, const char *device, int devnum)
{
    char path[1024];
    gchar *text = NULL;
    snprintf(path, sizeof path, "%s/%s", dir, device);
    if (!g_file_get_contents(path, &text, NULL, NULL))
        return NULL;
    char node[32], attr[32], prop[32];
    snprintf(node, sizeof node, "usb/001/%03d", devnum);
    snprintf(attr, sizeof attr, "devnum=%d\\n", devnum);
    snprintf(prop, sizeof prop, "DEVNUM=%03d", devnum);
    const char *from[] = {"usb/001/005", "devnum=5\\n", "DEVNUM=005"};
    const char *to[] = {node, attr, prop};
    for (int i = 0; i < 3; i++) {
        gchar **parts = g_strsplit(text, from[i], -1);
        g_free(text);
        text = g_strjoinv(to[i], parts);
        g_strfreev(parts);
    }
    return text;
}

/* The ioctl script goes first: adding the device sends the "add" uevents
 * itself, and the service opens the device as soon as it sees them. */
static bool plug(UMockdevTestbed *tb, const char *dir, const char *device, const char *script, int devnum)
{
    char path[1024], node[64];
    GError *error = NULL;
    snprintf(path, sizeof path, "%s/%s", dir, script);
    snprintf(node, sizeof node, "/dev/bus/usb/001/%03d", devnum);
    if (!umockdev_testbed_load_ioctl(tb, node, path, &error)) {
        fprintf(stderr, "loading %s: %s\n", path, error->message);
        g_error_free(error);
        return false;
    }
    gchar *text = device_text(dir, device, devnum);
    bool added = text && umockdev_testbed_add_from_string(tb, text, &error);
    if (!added) {
        fprintf(stderr, "adding %s: %s\n", device, error ? error->message : "unreadable");
        g_clear_error(&error);
    }
    g_free(text);
    return added;
}

static void unplug(UMockdevTestbed *tb)
{
    umockdev_testbed_uevent(tb, DEVICE_SYSFS, "remove");
    umockdev_testbed_remove_device(tb, INTERFACE_SYSFS);
    umockdev_testbed_remove_device(tb, DEVICE_SYSFS);
    umockdev_testbed_remove_device(tb, HUB_SYSFS);
}

static void expect_arrival(fc_spacemouse *sm, uint16_t product)
{
    fc_sm_event ev;
    bool got = next_non_report(sm, &ev, NULL);
    CHECK_MSG(got && ev.type == FC_SM_EVENT_ARRIVED, "no arrival of %04x (got %d: %s)", product,
              got ? (int)ev.type : -1, got ? ev.message : "nothing");
    CHECK(ev.product == product);
}

/* Plugged in while running, held, pulled out: ARRIVED, reports, LEFT. */
static void held_then_removed(fc_spacemouse *sm, UMockdevTestbed *tb, const char *dir)
{
    CHECK(plug(tb, dir, "compact.umockdev", "compact_hold.ioctl", 5));
    expect_arrival(sm, 0xc635);
    fc_sm_event ev;
    for (int i = 0; i < 3; i++) {
        CHECK(fc_spacemouse_next(sm, &ev, WAIT_MS) && ev.type == FC_SM_EVENT_REPORT);
        CHECK_MSG(ev.state.raw[0] == 100 && ev.kind == FC_SM_REPORT_SIX_AXIS, "held report %d: X %d", i,
                  ev.state.raw[0]);
    }
    unplug(tb);
    int reports = 0;
    bool got = next_non_report(sm, &ev, &reports);
    CHECK_MSG(got && ev.type == FC_SM_EVENT_LEFT, "no LEFT after the remove uevent (got %d)",
              got ? (int)ev.type : -1);
    CHECK_MSG(strcmp(ev.message, "unplugged") == 0, "left because \"%s\"", ev.message);
    printf("compact: arrived, streamed, left on the remove uevent (%d reports in between)\n", reports);
}

/* A different model after that one left: its scripted reports, then -19. */
static void second_device(fc_spacemouse *sm, UMockdevTestbed *tb, const char *dir)
{
    CHECK(plug(tb, dir, "navigator.umockdev", "navigator.ioctl", 6));
    expect_arrival(sm, 0xc626);
    int reports = 0;
    fc_sm_event ev;
    bool got = next_non_report(sm, &ev, &reports);
    CHECK_MSG(got && ev.type == FC_SM_EVENT_LEFT, "navigator did not leave (got %d)", got ? (int)ev.type : -1);
    CHECK_MSG(reports == 7, "navigator sent %d reports, its script 7", reports);
    CHECK(ev.state.raw[0] == 0 && ev.state.raw[5] == 0 && ev.state.buttons == 0);
    unplug(tb);
    printf("navigator: arrived, %d reports, left on URB status -19\n", reports);
}

static double seconds_since(const struct timespec *t0)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)(t.tv_sec - t0->tv_sec) + 1e-9 * (double)(t.tv_nsec - t0->tv_nsec);
}

/* A device that cannot be used (here: its only interface is not HID) is a
 * NOTICE saying why, and the service carries on with the next one plugged in.
 * (Permission denied cannot be staged: umockdev's preload answers every open
 * of a usbdevfs node itself, whatever the node's mode, so the "no permission"
 * message is checked in test_spacemouse_messages.) */
static void unusable_then_usable(UMockdevTestbed *tb, const char *dir)
{
    gchar *text = device_text(dir, "compact.umockdev", 8);
    CHECK(text != NULL);
    if (!text)
        return;
    /* interface descriptor: class 03 (HID) -> ff (vendor specific) */
    gchar **parts = g_strsplit(text, "090400000103", -1);
    gchar *vendor_class = g_strjoinv("0904000001FF", parts);
    g_strfreev(parts);
    GError *error = NULL;
    fc_spacemouse_options options;
    fc_spacemouse_options_default(&options);
    fc_spacemouse *sm;
    fc_error err;
    CHECK(fc_spacemouse_start(&options, &sm, &err) == FC_OK);
    CHECK(umockdev_testbed_add_from_string(tb, vendor_class, &error));
    g_clear_error(&error);
    g_free(vendor_class);
    g_free(text);
    fc_sm_event ev;
    bool got = next_non_report(sm, &ev, NULL);
    CHECK_MSG(got && ev.type == FC_SM_EVENT_NOTICE, "no NOTICE for an unusable device (got %d)",
              got ? (int)ev.type : -1);
    CHECK_MSG(strstr(ev.message, "no HID interrupt IN endpoint") != NULL, "notice \"%s\"", ev.message);
    printf("unusable device: %s\n", ev.message);
    unplug(tb);
    CHECK(plug(tb, dir, "navigator.umockdev", "navigator.ioctl", 9));
    expect_arrival(sm, 0xc626);
    int reports = 0;
    got = next_non_report(sm, &ev, &reports);
    CHECK_MSG(got && ev.type == FC_SM_EVENT_LEFT && reports == 7, "after the notice: %d reports, event %d",
              reports, got ? (int)ev.type : -1);
    fc_spacemouse_stop(sm);
    unplug(tb);
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: test_spacemouse_hotplug DIR\n");
        return 2;
    }
    UMockdevTestbed *tb = umockdev_testbed_new();
    if (!umockdev_in_mock_environment()) {
        printf("not under umockdev-wrapper: skipped\n");
        g_object_unref(tb);
        return SKIP;
    }
    fc_spacemouse_options options;
    fc_spacemouse_options_default(&options);
    fc_spacemouse *sm;
    fc_error err;
    if (fc_spacemouse_start(&options, &sm, &err) != FC_OK) {
        fprintf(stderr, "start: %s\n", err.message);
        return 1;
    }
    fc_sm_event ev;
    CHECK_MSG(!fc_spacemouse_next(sm, &ev, 300), "an event (%d) with no device", ev.type);
    held_then_removed(sm, tb, argv[1]);
    second_device(sm, tb, argv[1]);
    /* stopping while a transfer is in flight */
    CHECK(plug(tb, argv[1], "compact.umockdev", "compact_hold.ioctl", 7));
    expect_arrival(sm, 0xc635);
    CHECK(fc_spacemouse_next(sm, &ev, WAIT_MS) && ev.type == FC_SM_EVENT_REPORT);
    struct timespec t0;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    fc_spacemouse_stop(sm);
    double stop_s = seconds_since(&t0);
    printf("stopped while streaming in %.3f s\n", stop_s);
    unplug(tb);
    unusable_then_usable(tb, argv[1]);
    g_object_unref(tb);
    return test_result();
}
