/* spacemouse.c — the service: libusb context, hotplug, the event thread. */
#include "spacemouse.h"

#include <libusb.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "fc_error.h"
#include "spacemouse_device.h"
#include "spacemouse_devices.h"

#define DEFAULT_QUEUE_CAPACITY 1024
#define MAX_PENDING 8
#define MAX_VENDORS 4
/* How long one libusb_handle_events call may block; stop interrupts it anyway. */
#define EVENT_WAIT_US 200000
/* How long stopping waits for the cancelled transfer to come back. */
#define CANCEL_WAIT_ROUNDS 10

struct fc_spacemouse {
    libusb_context *usb;
    pthread_t thread;
    bool thread_started;
    atomic_bool stop;
    fc_sm_queue *queue;
    fc_sm_clock clock;
    void (*wake)(void *ctx);
    void *wake_ctx;
    libusb_hotplug_callback_handle hotplug[MAX_VENDORS];
    size_t hotplug_count;
    /* Below: touched only by hotplug/transfer callbacks and the event thread,
     * which are the same thread once it runs (ENUMERATE callbacks run in
     * fc_spacemouse_start before the thread starts). */
    fc_sm_device device;
    bool has_device;
    libusb_device *pending[MAX_PENDING];   /* arrived, not yet opened (referenced) */
    size_t pending_count;
};

uint64_t fc_sm_monotonic_ns(void *unused)
{
    (void)unused;
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (uint64_t)t.tv_sec * 1000000000ull + (uint64_t)t.tv_nsec;
}

void fc_spacemouse_options_default(fc_spacemouse_options *o)
{
    memset(o, 0, sizeof *o);
    o->clock.now_ns = fc_sm_monotonic_ns;
}

/* ---- events ------------------------------------------------------------ */

static void event_for(const fc_spacemouse *sm, fc_sm_event_type type, uint16_t vendor,
                      uint16_t product, fc_sm_event *ev)
{
    memset(ev, 0, sizeof *ev);
    ev->type = type;
    ev->time_ns = sm->clock.now_ns(sm->clock.ctx);
    ev->vendor = vendor;
    ev->product = product;
    snprintf(ev->name, sizeof ev->name, "%s", fc_sm_device_name(vendor, product));
    fc_sm_state_init(&ev->state);
}

static void emit(fc_spacemouse *sm, const fc_sm_event *ev)
{
    fc_sm_queue_push(sm->queue, ev);
    if (sm->wake)
        sm->wake(sm->wake_ctx);
}

static void emit_device(fc_spacemouse *sm, fc_sm_event_type type, const fc_sm_device *d,
                        const char *message)
{
    fc_sm_event ev;
    event_for(sm, type, d->vendor, d->product, &ev);
    ev.bus = d->bus;
    ev.address = d->address;
    ev.state = d->state;
    snprintf(ev.message, sizeof ev.message, "%s", message ? message : "");
    emit(sm, &ev);
}

static void on_report(void *ctx, const fc_sm_device *d, const uint8_t *report, size_t length,
                      fc_sm_report_kind kind)
{
    fc_spacemouse *sm = ctx;
    fc_sm_event ev;
    event_for(sm, FC_SM_EVENT_REPORT, d->vendor, d->product, &ev);
    ev.bus = d->bus;
    ev.address = d->address;
    memcpy(ev.report, report, length < sizeof ev.report ? length : sizeof ev.report);
    ev.length = length;
    ev.kind = kind;
    ev.state = d->state;
    emit(sm, &ev);
}

/* ---- hotplug: callbacks only record; the event thread opens and closes ---- */

static bool is_spacemouse(libusb_device *device)
{
    struct libusb_device_descriptor desc;
    return libusb_get_device_descriptor(device, &desc) == 0 &&
           fc_sm_device_supported(desc.idVendor, desc.idProduct);
}

static void add_pending(fc_spacemouse *sm, libusb_device *device)
{
    if (sm->pending_count < MAX_PENDING && is_spacemouse(device))
        sm->pending[sm->pending_count++] = libusb_ref_device(device);
}

static void remove_pending(fc_spacemouse *sm, libusb_device *device)
{
    for (size_t i = 0; i < sm->pending_count; i++) {
        if (sm->pending[i] != device)
            continue;
        libusb_unref_device(device);
        memmove(&sm->pending[i], &sm->pending[i + 1], (sm->pending_count - i - 1) * sizeof *sm->pending);
        sm->pending_count--;
        return;
    }
}

/* No synchronous I/O is allowed here, and LEFT must not close the handle:
 * both only note what happened for the event thread. */
static int LIBUSB_CALL hotplug_event(libusb_context *usb, libusb_device *device,
                                     libusb_hotplug_event event, void *ctx)
{
    (void)usb;
    fc_spacemouse *sm = ctx;
    if (event == LIBUSB_HOTPLUG_EVENT_DEVICE_ARRIVED) {
        add_pending(sm, device);
    } else if (sm->has_device && sm->device.device == device) {
        if (!sm->device.gone)
            snprintf(sm->device.gone_reason, sizeof sm->device.gone_reason, "unplugged");
        sm->device.gone = true;
        sm->device.closing = true;
    } else {
        remove_pending(sm, device);
    }
    return 0;   /* stay registered */
}

static fc_code watch_vendors(fc_spacemouse *sm, fc_error *err)
{
    for (size_t i = 0; i < fc_sm_vendor_count() && i < MAX_VENDORS; i++) {
        int rc = libusb_hotplug_register_callback(
            sm->usb, LIBUSB_HOTPLUG_EVENT_DEVICE_ARRIVED | LIBUSB_HOTPLUG_EVENT_DEVICE_LEFT,
            LIBUSB_HOTPLUG_ENUMERATE, fc_sm_vendor(i), LIBUSB_HOTPLUG_MATCH_ANY,
            LIBUSB_HOTPLUG_MATCH_ANY, hotplug_event, sm, &sm->hotplug[sm->hotplug_count]);
        if (rc != LIBUSB_SUCCESS)
            return fc_error_set(err, FC_ERR_IO, "libusb hotplug registration failed: %s",
                                libusb_strerror(rc));
        sm->hotplug_count++;
    }
    return FC_OK;
}

/* Without hotplug support (rare builds of libusb): the devices present now. */
static void enumerate_once(fc_spacemouse *sm)
{
    libusb_device **list = NULL;
    ssize_t n = libusb_get_device_list(sm->usb, &list);
    for (ssize_t i = 0; i < n; i++)
        add_pending(sm, list[i]);
    if (list)
        libusb_free_device_list(list, 1);
}

/* ---- the event thread ---------------------------------------------------- */

static void open_next_pending(fc_spacemouse *sm)
{
    while (!sm->has_device && sm->pending_count > 0) {
        libusb_device *device = sm->pending[0];
        memmove(&sm->pending[0], &sm->pending[1], (sm->pending_count - 1) * sizeof *sm->pending);
        sm->pending_count--;
        fc_error err;
        fc_code code = fc_sm_device_open(device, on_report, sm, &sm->device, &err);
        if (code == FC_OK && fc_sm_device_submit(&sm->device, &err) != FC_OK) {
            fc_sm_device_close(&sm->device);
            code = err.code;
        }
        if (code == FC_OK) {
            sm->has_device = true;
            emit_device(sm, FC_SM_EVENT_ARRIVED, &sm->device, NULL);
        } else {
            emit_device(sm, FC_SM_EVENT_NOTICE, &sm->device, err.message);
        }
        libusb_unref_device(device);
    }
}

/* A device that went away is closed once its transfer is back. */
static void close_if_gone(fc_spacemouse *sm)
{
    if (!sm->has_device || !sm->device.gone)
        return;
    fc_sm_device_cancel(&sm->device);
    if (sm->device.in_flight)
        return;
    fc_sm_device_close(&sm->device);
    sm->has_device = false;
    emit_device(sm, FC_SM_EVENT_LEFT, &sm->device, sm->device.gone_reason);
}

static void handle_events_once(fc_spacemouse *sm)
{
    struct timeval wait = {0, EVENT_WAIT_US};
    libusb_handle_events_timeout_completed(sm->usb, &wait, NULL);
}

static void shut_device(fc_spacemouse *sm)
{
    if (!sm->has_device)
        return;
    fc_sm_device_cancel(&sm->device);
    for (int i = 0; i < CANCEL_WAIT_ROUNDS && sm->device.in_flight; i++)
        handle_events_once(sm);
    /* A transfer libusb never returned cannot be freed safely: leak it rather
     * than risk a use after free (never seen; the round limit only bounds exit). */
    if (sm->device.in_flight)
        sm->device.transfer = NULL;
    fc_sm_device_close(&sm->device);
    sm->has_device = false;
}

static void *event_thread(void *arg)
{
    fc_spacemouse *sm = arg;
    while (!atomic_load(&sm->stop)) {
        close_if_gone(sm);
        open_next_pending(sm);
        handle_events_once(sm);
    }
    shut_device(sm);
    return NULL;
}

/* ---- start / next / stop -------------------------------------------------- */

static fc_code start_usb(fc_spacemouse *sm, fc_error *err)
{
    int rc = libusb_init(&sm->usb);
    if (rc != 0) {
        sm->usb = NULL;
        return fc_error_set(err, FC_ERR_IO, "libusb could not start: %s", libusb_strerror(rc));
    }
    if (libusb_has_capability(LIBUSB_CAP_HAS_HOTPLUG)) {
        fc_code code = watch_vendors(sm, err);
        if (code != FC_OK)
            return code;
    } else {
        enumerate_once(sm);
    }
    if (pthread_create(&sm->thread, NULL, event_thread, sm) != 0)
        return fc_error_set(err, FC_ERR_IO, "could not start the SpaceMouse event thread");
    sm->thread_started = true;
    return FC_OK;
}

fc_code fc_spacemouse_start(const fc_spacemouse_options *options, fc_spacemouse **out, fc_error *err)
{
    *out = NULL;
    fc_spacemouse *sm = calloc(1, sizeof *sm);
    if (!sm)
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for the SpaceMouse service");
    atomic_init(&sm->stop, false);
    sm->clock = options->clock;
    if (!sm->clock.now_ns)
        sm->clock = (fc_sm_clock){fc_sm_monotonic_ns, NULL};
    sm->wake = options->wake;
    sm->wake_ctx = options->wake_ctx;
    size_t capacity = options->queue_capacity ? options->queue_capacity : DEFAULT_QUEUE_CAPACITY;
    fc_code code = fc_sm_queue_create(capacity, &sm->queue, err);
    if (code == FC_OK)
        code = start_usb(sm, err);
    if (code != FC_OK) {
        fc_spacemouse_stop(sm);
        return code;
    }
    *out = sm;
    return FC_OK;
}

bool fc_spacemouse_next(fc_spacemouse *sm, fc_sm_event *event, int timeout_ms)
{
    return fc_sm_queue_pop(sm->queue, event, timeout_ms);
}

void fc_spacemouse_stop(fc_spacemouse *sm)
{
    if (!sm)
        return;
    if (sm->thread_started) {
        atomic_store(&sm->stop, true);
        libusb_interrupt_event_handler(sm->usb);
        pthread_join(sm->thread, NULL);
    }
    for (size_t i = 0; i < sm->hotplug_count; i++)
        libusb_hotplug_deregister_callback(sm->usb, sm->hotplug[i]);
    while (sm->pending_count > 0)
        libusb_unref_device(sm->pending[--sm->pending_count]);
    if (sm->usb)
        libusb_exit(sm->usb);
    fc_sm_queue_destroy(sm->queue);
    free(sm);
}
