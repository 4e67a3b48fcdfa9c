/* readback.h — a render target's colour texture into a CPU fc_image. */
#ifndef FC_READBACK_H
#define FC_READBACK_H

#include <stdint.h>

#include "../image.h"
#include "render_target.h"

/* Reads the target as `channels` (1 = red only, 3 = RGB, 4 = RGBA) of `type` into out,
 * rows top to bottom (GL's are bottom to top). out's buffer is reused and only
 * grows. FC_ERR_NOMEM when it cannot grow. */
fc_code fc_readback(const fc_render_target *target, uint32_t channels, fc_pixel_type type, fc_image *out,
                    fc_error *err);

#endif
