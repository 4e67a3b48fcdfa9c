/* spacemouse_usb_error.c — libusb failures into actionable messages. */
#include "spacemouse_usb_error.h"

#include <libusb.h>

#include "fc_error.h"
#include "spacemouse_devices.h"

fc_code fc_sm_usb_error(int rc, const char *step, const fc_sm_device_id *d, fc_error *err)
{
    const char *name = fc_sm_device_name(d->vendor, d->product);
    if (rc == LIBUSB_ERROR_ACCESS)
        return fc_error_set(err, FC_ERR_IO,
                            "no permission to open %s (%04x:%04x, bus %u device %u): install %s "
                            "(docs/viewer.md, SpaceMouse) and re-plug it",
                            name, d->vendor, d->product, d->bus, d->address, FC_SM_UDEV_RULE);
    if (rc == LIBUSB_ERROR_BUSY)
        return fc_error_set(err, FC_ERR_IO, "%s (%04x:%04x) is claimed by another libusb program: %s failed",
                            name, d->vendor, d->product, step);
    return fc_error_set(err, FC_ERR_IO, "%s (%04x:%04x): %s failed: %s", name, d->vendor, d->product, step,
                        libusb_strerror(rc));
}
