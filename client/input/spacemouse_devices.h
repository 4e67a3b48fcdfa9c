/* spacemouse_devices.h — which USB devices are 6-DOF SpaceMice.
 *
 * 3Dconnexion's own vendor id 0x256f covers SpaceMice and also mice and
 * keyboards that have no puck, so every 256f product is accepted except a
 * short list of non-6-DOF models. The older devices carry Logitech's vendor id
 * 0x046d, which also covers thousands of unrelated mice and keyboards: only the
 * listed product ids are accepted there. */
#ifndef FC_SPACEMOUSE_DEVICES_H
#define FC_SPACEMOUSE_DEVICES_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#define FC_SM_VENDOR_3DCONNEXION 0x256fu
#define FC_SM_VENDOR_LOGITECH 0x046du

/* The vendor ids to watch (hotplug registers once per vendor). */
size_t fc_sm_vendor_count(void);
uint16_t fc_sm_vendor(size_t index);

/* True for a 6-DOF SpaceMouse. */
bool fc_sm_device_supported(uint16_t vendor, uint16_t product);

/* The model's name for messages: a known name, or a generic one for an
 * accepted but unlisted 256f product ("3Dconnexion device"). */
const char *fc_sm_device_name(uint16_t vendor, uint16_t product);

#endif
