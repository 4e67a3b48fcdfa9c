/* fluid_blocks.h — the 8x8-pixel blocks of a depth image that hold fluid, as
 * a buffer for an indirect dispatch with one workgroup per such block: a
 * compute filter that leaves the background (depth 0) alone runs on those
 * blocks only (on llvmpipe a dispatch over the whole image costs every block,
 * whatever the shader skips). The shader side: fluid_blocks.comp.glsl, and the
 * FluidBlocks buffer the filters read. */
#ifndef FC_FLUID_BLOCKS_H
#define FC_FLUID_BLOCKS_H

#include <epoxy/gl.h>
#include <stdint.h>

#include "fluidcast_types.h"
#include "gpu_memory.h"
#include "render_target.h"

/* Pixels per block side (BLOCK of the shaders). */
#define FC_FLUID_BLOCK 8u

typedef struct fc_fluid_blocks {
    GLuint program;         /* fluid_blocks.comp.glsl */
    GLuint buffer;          /* 3 workgroup counts, then one uint per listed block */
    uint32_t capacity;      /* blocks the buffer holds: those of the largest image listed */
    uint64_t bytes;         /* its size; 0 when not allocated */
    uint32_t allocations;   /* times it was (re)allocated */
} fc_fluid_blocks;

fc_code fc_fluid_blocks_create(const char *shader_dir, fc_fluid_blocks *b, fc_error *err);
void fc_fluid_blocks_destroy(fc_fluid_blocks *b);

/* Lists the blocks of `depth`'s image in use that hold a texel > 0 (the
 * buffer grows to the image's blocks when it is larger than ever before).
 * Leaves another program bound: the caller binds its own afterwards. */
fc_code fc_fluid_blocks_find(fc_fluid_blocks *b, const fc_render_target *depth, fc_error *err);

/* Runs the current compute program with one workgroup per listed block, the
 * list bound as shader storage buffer `binding`, then makes its image stores
 * visible to texture fetches and framebuffer reads (as
 * fc_gl_dispatch_over_image). */
void fc_fluid_blocks_dispatch(const fc_fluid_blocks *b, GLuint binding);

/* Frees the buffer; the next find allocates it at its image's size. */
void fc_fluid_blocks_release(fc_fluid_blocks *b);

/* Adds the buffer's bytes and allocations to m's render targets (it is sized
 * by the image, like them). */
void fc_fluid_blocks_tally(const fc_fluid_blocks *b, fc_gpu_memory *m);

#endif
