/* spacemouse_usb_error.h — a failed libusb step on a SpaceMouse as a message
 * the user can act on (permission denied names the udev rule to install). */
#ifndef FC_SPACEMOUSE_USB_ERROR_H
#define FC_SPACEMOUSE_USB_ERROR_H

#include <stdint.h>

#include "fluidcast_types.h"

#define FC_SM_UDEV_RULE "deploy/udev/70-fluidcast-spacemouse.rules"

/* Which device failed, for the message. */
typedef struct fc_sm_device_id {
    uint16_t vendor, product;
    uint8_t bus, address;
} fc_sm_device_id;

/* Fills err for libusb error `rc` (LIBUSB_ERROR_*) during `step` ("opening",
 * "claiming the interface", ...) and returns FC_ERR_IO. */
fc_code fc_sm_usb_error(int rc, const char *step, const fc_sm_device_id *device, fc_error *err);

#endif
