/* spacemouse_device.h — one opened SpaceMouse: its claimed HID interface and
 * the single asynchronous interrupt transfer kept in flight on it.
 *
 * Only the service's event thread calls these (and libusb calls the transfer
 * callback on that thread, inside libusb_handle_events*), so nothing here
 * needs a lock. */
#ifndef FC_SPACEMOUSE_DEVICE_H
#define FC_SPACEMOUSE_DEVICE_H

#include <libusb.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "fluidcast_types.h"
#include "spacemouse_decode.h"
#include "spacemouse_events.h"

typedef struct fc_sm_device fc_sm_device;

/* Called for every completed transfer, after the report was decoded into
 * device->state; `kind` says what the report was. */
typedef void (*fc_sm_report_sink)(void *ctx, const fc_sm_device *device, const uint8_t *report,
                                  size_t length, fc_sm_report_kind kind);

struct fc_sm_device {
    libusb_device *device;            /* referenced while open */
    libusb_device_handle *handle;
    struct libusb_transfer *transfer; /* the one transfer, reused */
    uint8_t buffer[FC_SM_REPORT_MAX];
    int interface;
    uint8_t endpoint;
    bool detached;                    /* we detached usbhid: re-attach on close */
    bool claimed;
    bool in_flight;
    bool closing;                     /* no resubmission: stopping or gone */
    bool cancel_sent;
    bool gone;                        /* unplugged or failed: close it outside callbacks */
    int failures;                     /* consecutive failed transfers */
    char gone_reason[128];
    uint16_t vendor, product;
    uint8_t bus, address;
    fc_sm_state state;
    fc_sm_report_sink sink;
    void *sink_ctx;
};

/* Opens `device`, finds its HID interface's interrupt IN endpoint, detaches
 * the kernel driver only if one is active, and claims the interface. On
 * failure nothing stays open and err says why (permission denied names the
 * udev rule). */
fc_code fc_sm_device_open(libusb_device *device, fc_sm_report_sink sink, void *sink_ctx,
                          fc_sm_device *out, fc_error *err);

/* Submits the interrupt transfer (64 bytes; actual_length is what counts).
 * Resubmitted by its own callback until the device closes or goes. */
fc_code fc_sm_device_submit(fc_sm_device *device, fc_error *err);

/* Stops resubmitting and cancels the transfer if it is in flight; the caller
 * keeps handling events until device->in_flight is false. */
void fc_sm_device_cancel(fc_sm_device *device);

/* Releases the interface, re-attaches the kernel driver if we detached it,
 * closes. The transfer must not be in flight. Errors of an unplugged device
 * are expected and ignored. */
void fc_sm_device_close(fc_sm_device *device);

#endif
