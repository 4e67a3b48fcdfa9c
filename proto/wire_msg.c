/* wire_msg.c — the names of the message types (wire.h's FC_MSG_TYPES). */
#include "wire.h"

#include <stddef.h>

const char *fc_msg_name(uint16_t type)
{
#define FC_MSG_NAME_CASE(name, number) \
    case FC_MSG_##name: return #name;
    switch (type) {
        FC_MSG_TYPES(FC_MSG_NAME_CASE)
    }
#undef FC_MSG_NAME_CASE
    return NULL;
}
