/* spacemouse_device.c — open/claim/transfer/close of one SpaceMouse. */
#include "spacemouse_device.h"

#include <stdio.h>
#include <string.h>

#include "fc_error.h"
#include "spacemouse_devices.h"
#include "spacemouse_usb_error.h"

#define HID_CLASS 3
/* Transient transfer errors tolerated in a row before the device is dropped. */
#define MAX_FAILURES 3

static void LIBUSB_CALL transfer_done(struct libusb_transfer *transfer);

/* The first HID interface with an interrupt IN endpoint: interface 0 on wired
 * devices and on the Universal Receiver (whose other interfaces are keyboard
 * and mouse). */
static bool find_endpoint(const struct libusb_config_descriptor *config, int *interface,
                          uint8_t *endpoint)
{
    for (int i = 0; i < config->bNumInterfaces; i++) {
        if (config->interface[i].num_altsetting < 1)
            continue;
        const struct libusb_interface_descriptor *alt = &config->interface[i].altsetting[0];
        if (alt->bInterfaceClass != HID_CLASS)
            continue;
        for (int e = 0; e < alt->bNumEndpoints; e++) {
            const struct libusb_endpoint_descriptor *ep = &alt->endpoint[e];
            if ((ep->bEndpointAddress & LIBUSB_ENDPOINT_IN) &&
                (ep->bmAttributes & 3) == LIBUSB_TRANSFER_TYPE_INTERRUPT) {
                *interface = alt->bInterfaceNumber;
                *endpoint = ep->bEndpointAddress;
                return true;
            }
        }
    }
    return false;
}

static fc_code open_failure(const fc_sm_device *d, int rc, const char *step, fc_error *err)
{
    fc_sm_device_id id = {d->vendor, d->product, d->bus, d->address};
    return fc_sm_usb_error(rc, step, &id, err);
}

static void describe(libusb_device *device, fc_sm_device *d)
{
    struct libusb_device_descriptor desc;
    if (libusb_get_device_descriptor(device, &desc) == 0) {
        d->vendor = desc.idVendor;
        d->product = desc.idProduct;
    }
    d->bus = libusb_get_bus_number(device);
    d->address = libusb_get_device_address(device);
}

static fc_code locate_endpoint(fc_sm_device *d, fc_error *err)
{
    struct libusb_config_descriptor *config = NULL;
    int rc = libusb_get_active_config_descriptor(d->device, &config);
    if (rc != 0)
        return open_failure(d, rc, "reading the configuration descriptor", err);
    bool found = find_endpoint(config, &d->interface, &d->endpoint);
    libusb_free_config_descriptor(config);
    if (!found)
        return fc_error_set(err, FC_ERR_IO, "%s (%04x:%04x) has no HID interrupt IN endpoint",
                            fc_sm_device_name(d->vendor, d->product), d->vendor, d->product);
    return FC_OK;
}

/* usbhid owns the interface: detach it only when libusb says it is active
 * (auto-detach would also try when it is not, and fails under umockdev). */
static fc_code claim(fc_sm_device *d, fc_error *err)
{
    int active = libusb_kernel_driver_active(d->handle, d->interface);
    if (active == 1) {
        int rc = libusb_detach_kernel_driver(d->handle, d->interface);
        if (rc != 0)
            return open_failure(d, rc, "detaching the kernel driver", err);
        d->detached = true;
    }
    int rc = libusb_claim_interface(d->handle, d->interface);
    if (rc != 0)
        return open_failure(d, rc, "claiming the interface", err);
    d->claimed = true;
    return FC_OK;
}

fc_code fc_sm_device_open(libusb_device *device, fc_sm_report_sink sink, void *sink_ctx,
                          fc_sm_device *d, fc_error *err)
{
    memset(d, 0, sizeof *d);
    fc_sm_state_init(&d->state);
    d->sink = sink;
    d->sink_ctx = sink_ctx;
    describe(device, d);
    d->device = libusb_ref_device(device);
    fc_code code = locate_endpoint(d, err);
    if (code == FC_OK) {
        int rc = libusb_open(device, &d->handle);
        if (rc != 0)
            code = open_failure(d, rc, "opening", err);
    }
    if (code == FC_OK)
        code = claim(d, err);
    if (code == FC_OK && !(d->transfer = libusb_alloc_transfer(0)))
        code = fc_error_set(err, FC_ERR_NOMEM, "no memory for a USB transfer");
    if (code != FC_OK)
        fc_sm_device_close(d);
    return code;
}

static void mark_gone(fc_sm_device *d, const char *fmt, const char *detail)
{
    d->gone = true;
    d->closing = true;
    snprintf(d->gone_reason, sizeof d->gone_reason, fmt, detail);
}

static int submit(fc_sm_device *d)
{
    libusb_fill_interrupt_transfer(d->transfer, d->handle, d->endpoint, d->buffer, sizeof d->buffer,
                                   transfer_done, d, 0);
    int rc = libusb_submit_transfer(d->transfer);
    d->in_flight = rc == 0;
    return rc;
}

fc_code fc_sm_device_submit(fc_sm_device *d, fc_error *err)
{
    int rc = submit(d);
    if (rc != 0)
        return open_failure(d, rc, "submitting the interrupt transfer", err);
    return FC_OK;
}

static void resubmit(fc_sm_device *d)
{
    if (d->closing)
        return;
    int rc = submit(d);
    if (rc == LIBUSB_ERROR_NO_DEVICE)
        mark_gone(d, "%s", "unplugged");
    else if (rc != 0)
        mark_gone(d, "resubmitting the transfer failed: %s", libusb_strerror(rc));
}

static const char *status_name(enum libusb_transfer_status status)
{
    switch (status) {
    case LIBUSB_TRANSFER_ERROR: return "transfer error";
    case LIBUSB_TRANSFER_TIMED_OUT: return "timed out";
    case LIBUSB_TRANSFER_STALL: return "endpoint stalled";
    case LIBUSB_TRANSFER_OVERFLOW: return "overflow";
    default: return "unexpected status";
    }
}

/* Runs on the event thread inside libusb_handle_events*. */
static void LIBUSB_CALL transfer_done(struct libusb_transfer *t)
{
    fc_sm_device *d = t->user_data;
    d->in_flight = false;
    switch (t->status) {
    case LIBUSB_TRANSFER_COMPLETED: {
        size_t length = t->actual_length > 0 ? (size_t)t->actual_length : 0;
        fc_sm_report_kind kind = fc_sm_decode(&d->state, t->buffer, length);
        d->failures = 0;
        if (!d->closing)
            d->sink(d->sink_ctx, d, t->buffer, length, kind);
        resubmit(d);
        return;
    }
    case LIBUSB_TRANSFER_NO_DEVICE:   /* URB status -19 (ENODEV): unplugged, not an error */
        mark_gone(d, "%s", "unplugged");
        return;
    case LIBUSB_TRANSFER_CANCELLED:
        return;
    default:
        if (++d->failures < MAX_FAILURES)
            resubmit(d);
        else
            mark_gone(d, "dropped after repeated transfer errors (%s)", status_name(t->status));
        return;
    }
}

void fc_sm_device_cancel(fc_sm_device *d)
{
    d->closing = true;
    if (d->in_flight && !d->cancel_sent) {
        d->cancel_sent = true;
        /* NOT_FOUND: it completed already; its callback still comes and
         * clears in_flight, so the transfer is never freed under libusb. */
        libusb_cancel_transfer(d->transfer);
    }
}

void fc_sm_device_close(fc_sm_device *d)
{
    if (d->claimed)
        libusb_release_interface(d->handle, d->interface);
    if (d->detached)
        libusb_attach_kernel_driver(d->handle, d->interface);
    if (d->handle)
        libusb_close(d->handle);
    if (d->transfer)
        libusb_free_transfer(d->transfer);
    if (d->device)
        libusb_unref_device(d->device);
    d->handle = NULL;
    d->transfer = NULL;
    d->device = NULL;
    d->claimed = d->detached = false;
}
