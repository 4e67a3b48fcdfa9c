/* bench_output.h — files the benchmark writes: scenes as particle files, so a
 * peer renderer (bench/peer/) reads exactly the particles fluidcast renders,
 * and encoded images, so the two renderers' pictures can be compared by eye. */
#ifndef FC_BENCH_OUTPUT_H
#define FC_BENCH_OUTPUT_H

#include <stddef.h>

#include "fluidcast_types.h"

/* Writes the positions as .f32: raw little-endian float32 x y z triples, no
 * header (the format client/readers reads). FC_ERR_IO naming the path. */
fc_code bench_write_scene_f32(const fc_frame *frame, const char *path, fc_error *err);

/* Writes `size` bytes to `path`, replacing it. FC_ERR_IO naming the path. */
fc_code bench_write_bytes(const void *data, size_t size, const char *path, fc_error *err);

#endif
