/* bench_memory.c — GPU memory as the pipeline counts it and as the driver does. */
#include "bench_memory.h"

#include <epoxy/gl.h>
#include <stdio.h>

#define MIB (1024.0 * 1024.0)

static int64_t driver_free_kib(void)
{
    GLint kib = 0;
    glGetIntegerv(GL_GPU_MEMORY_INFO_CURRENT_AVAILABLE_VIDMEM_NVX, &kib);
    return kib;
}

void bench_memory_start(bench_memory *m)
{
    m->driver_reports = epoxy_has_gl_extension("GL_NVX_gpu_memory_info");
    m->baseline_free_kib = m->driver_reports ? driver_free_kib() : 0;
}

void bench_memory_print_cell(const bench_memory *m, const fc_pipeline *pipe)
{
    fc_gpu_memory mem;
    fc_pipeline_gpu_memory(pipe, &mem);
    printf(" %.1f", (double)fc_gpu_memory_total(&mem) / MIB);
    /* The driver's figure also holds shaders, queries and its own staging. */
    if (m->driver_reports)
        printf(" (driver %.1f)", (double)(m->baseline_free_kib - driver_free_kib()) / 1024.0);
    printf(" |");
}

void bench_memory_print_split(const fc_pipeline *pipe)
{
    fc_gpu_memory mem;
    fc_pipeline_gpu_memory(pipe, &mem);
    printf("GPU memory: particles %.2f MiB, render targets %.2f MiB, readback %.2f MiB, total %.2f MiB"
           " (%llu allocations so far)\n\n",
           (double)mem.particle_bytes / MIB, (double)mem.render_target_bytes / MIB, (double)mem.readback_bytes / MIB,
           (double)fc_gpu_memory_total(&mem) / MIB, (unsigned long long)mem.allocations);
}
