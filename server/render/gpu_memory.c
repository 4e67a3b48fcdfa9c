/* gpu_memory.c — totals of the pipeline's GPU memory. */
#include "gpu_memory.h"

uint64_t fc_gpu_memory_total(const fc_gpu_memory *m)
{
    return m->particle_bytes + m->render_target_bytes + m->readback_bytes;
}
