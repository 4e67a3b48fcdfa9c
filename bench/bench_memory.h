/* bench_memory.h — the GPU memory column of fluidcast-bench: the pipeline's
 * own accounting (fc_pipeline_gpu_memory) and, where the driver reports its
 * free video memory (GL_NVX_gpu_memory_info, NVIDIA), the driver's figure for
 * what was taken since the baseline, next to it. */
#ifndef FC_BENCH_MEMORY_H
#define FC_BENCH_MEMORY_H

#include <stdbool.h>
#include <stdint.h>

#include "pipeline.h"

typedef struct bench_memory {
    bool driver_reports;          /* GL_NVX_gpu_memory_info is there */
    int64_t baseline_free_kib;    /* free video memory when bench_memory_start ran */
} bench_memory;

/* Takes the driver's baseline, if it has one; needs the current GL context. */
void bench_memory_start(bench_memory *m);

/* The table cell: the pipeline's total in MiB, with the driver's "(driver N)"
 * where it reports one. */
void bench_memory_print_cell(const bench_memory *m, const fc_pipeline *pipe);

/* One line with the split: particles, render targets, readback, allocations. */
void bench_memory_print_split(const fc_pipeline *pipe);

#endif
