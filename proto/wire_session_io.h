/* wire_session_io.h — internal to the proto libraries: starting messages of the
 * session types, which are not members of fc_msg_type (wire_io.h). */
#ifndef FC_WIRE_SESSION_IO_H
#define FC_WIRE_SESSION_IO_H

#include "wire_io.h"

/* wire_begin_message for a type from wire_session.h. */
size_t begin_session_message(fc_buf *out, int type, uint32_t request_id, uint32_t length);

#endif
