/* test_spacemouse_messages.c — what a user reads when a SpaceMouse cannot be
 * used: permission denied names the udev rule and the device (the path
 * umockdev cannot stage, see test_spacemouse_hotplug.c), a device claimed by
 * another program says so, anything else names the step and libusb's reason. */
#include <libusb.h>
#include <string.h>

#include "spacemouse_usb_error.h"
#include "test_util.h"

int main(void)
{
    fc_sm_device_id compact = {0x256f, 0xc635, 1, 5};
    fc_error err;
    CHECK_CODE(fc_sm_usb_error(LIBUSB_ERROR_ACCESS, "opening", &compact, &err), FC_ERR_IO);
    CHECK(err.code == FC_ERR_IO);
    CHECK_MSG(strstr(err.message, "no permission to open SpaceMouse Compact (256f:c635, bus 1 device 5)") &&
                  strstr(err.message, "deploy/udev/70-fluidcast-spacemouse.rules"),
              "%s", err.message);
    fc_sm_device_id navigator = {0x046d, 0xc626, 3, 12};
    fc_sm_usb_error(LIBUSB_ERROR_BUSY, "claiming the interface", &navigator, &err);
    CHECK_MSG(strstr(err.message, "SpaceNavigator (046d:c626) is claimed by another libusb program") != NULL,
              "%s", err.message);
    fc_sm_usb_error(LIBUSB_ERROR_IO, "submitting the interrupt transfer", &navigator, &err);
    CHECK_MSG(strstr(err.message, "submitting the interrupt transfer failed: ") != NULL, "%s", err.message);
    CHECK(strstr(err.message, "udev") == NULL);
    return test_result();
}
