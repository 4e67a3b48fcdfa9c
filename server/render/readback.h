/* readback.h — a render target's colour texture into a CPU fc_image, through
 * a pixel-pack buffer.
 *
 * Why a buffer: on a discrete GPU glReadPixels into client memory stalls
 * until the copy has crossed the bus into pageable memory; into a pack buffer
 * it is a DMA into memory the driver keeps mapped, and the CPU only waits on
 * a fence before copying the rows out (turned top-down on the way, instead of
 * a separate pass). It keeps the door open for a readback that overlaps the
 * next frame (start the copy, fence, map later), which the synchronous
 * fc_pipeline_render does not do. */
#ifndef FC_READBACK_H
#define FC_READBACK_H

#include <epoxy/gl.h>
#include <stddef.h>
#include <stdint.h>

#include "image.h"
#include "gpu_memory.h"
#include "render_target.h"

typedef struct fc_readback {
    GLuint pack_buffer;        /* persistently mapped for reading; 0 before the first readback */
    const unsigned char *mapped;
    size_t capacity;           /* its bytes; it only grows */
    uint32_t allocations;      /* times the pack buffer was (re)allocated */
} fc_readback;

/* An empty readback: the buffer is made by the first fc_readback_run. */
fc_readback fc_readback_init(void);
void fc_readback_release(fc_readback *r);

/* Reads the target as `channels` (1 = red only, 3 = RGB, 4 = RGBA) of `type` into out,
 * rows top to bottom (GL's are bottom to top). out's buffer and the pack
 * buffer are reused and only grow. FC_ERR_NOMEM when out cannot grow,
 * FC_ERR_RENDER when the GPU has no room for the pack buffer. */
fc_code fc_readback_run(fc_readback *r, const fc_render_target *target, uint32_t channels, fc_pixel_type type,
                        fc_image *out, fc_error *err);

/* Adds the pack buffer's bytes and allocations to m's readback. */
void fc_readback_tally(const fc_readback *r, fc_gpu_memory *m);

#endif
