/* gpu_memory.h — the GPU memory a pipeline holds, as its resources' sizes and
 * internal formats imply: each resource records its bytes when it is
 * allocated, and the pipeline sums them (fc_pipeline_gpu_memory). Drivers may
 * pad or compress; these are the bytes the pipeline asked for. */
#ifndef FC_GPU_MEMORY_H
#define FC_GPU_MEMORY_H

#include <stdint.h>

typedef struct fc_gpu_memory {
    uint64_t particle_bytes;       /* positions (12 B) and shading records (16 B) per particle of the
                                      largest frame uploaded: the buffers only grow */
    uint64_t render_target_bytes;  /* colour textures, depth/stencil buffers, ping-pong and compute-splat
                                      images, each grown to the widest and highest image its stage rendered
                                      (they only grow, until fc_pipeline_trim) */
    uint64_t readback_bytes;       /* pixel-pack buffer of the largest image read back: it only grows */
    uint64_t allocations;          /* times any of them was (re)allocated since the pipeline was created */
} fc_gpu_memory;

/* particle + render target + readback bytes. */
uint64_t fc_gpu_memory_total(const fc_gpu_memory *m);

#endif
