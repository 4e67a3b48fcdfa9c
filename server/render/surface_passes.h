/* surface_passes.h — the GL programs of surface mesh extraction
 * (surface_extract.h), built once per pipeline, and the prefix sum they use
 * (anisotropy's scan shader, run over any buffer). */
#ifndef FC_SURFACE_PASSES_H
#define FC_SURFACE_PASSES_H

#include <epoxy/gl.h>
#include <stdint.h>

#include "fluidcast_types.h"

typedef struct fc_surface_passes {
    GLuint field_program, crossed_program, edges_program, cells_program, vertices_program, scan_program;
    GLint max_groups;   /* GL_MAX_COMPUTE_WORK_GROUP_COUNT along x */
} fc_surface_passes;

fc_code fc_surface_passes_create(const char *shader_dir, fc_surface_passes *s, fc_error *err);
void fc_surface_passes_destroy(fc_surface_passes *s);

/* One workgroup per block, in rows of at most max_groups. */
void fc_surface_dispatch_blocks(const fc_surface_passes *s, uint32_t blocks);

/* Entries a prefix sum of n values needs in its buffer (the values, one more
 * for the total, and the levels of block sums above them). */
uint64_t fc_surface_scan_entries(uint64_t n);

/* Exclusive prefix sum, in place, of the first n entries of `buffer` (which
 * holds fc_surface_scan_entries(n)); entry n receives the total. */
void fc_surface_scan(const fc_surface_passes *s, GLuint buffer, uint64_t n);

#endif
