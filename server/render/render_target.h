/* render_target.h — a framebuffer with one colour texture and an optional
 * depth and stencil buffer. The attachments only grow, per axis, to the
 * largest size asked for (or one more, never a power of two: fc_gl_non_pot);
 * a smaller image uses their lower-left corner, so alternating image sizes
 * allocate nothing. */
#ifndef FC_RENDER_TARGET_H
#define FC_RENDER_TARGET_H

#include <epoxy/gl.h>
#include <stdbool.h>
#include <stdint.h>

#include "fluidcast_types.h"
#include "gpu_memory.h"

typedef struct fc_render_target {
    GLuint framebuffer;
    GLuint color;           /* texture, sampled by later passes */
    GLuint depth;           /* GL_DEPTH32F_STENCIL8 renderbuffer, 0 without depth */
    GLenum color_format;    /* sized internal format, e.g. GL_R32F */
    bool with_depth;
    bool linear;            /* bilinear sampling of `color` */
    uint32_t width;         /* the image in use: the lower-left width x height of the attachments */
    uint32_t height;
    uint32_t texture_width; /* the attachments' size, >= width x height */
    uint32_t texture_height;
    uint64_t bytes;         /* GPU memory of the attachments, from their formats; 0 when not allocated */
    uint32_t allocations;   /* times the attachments were (re)allocated */
} fc_render_target;

/* A target of `color_format` that is not allocated yet; zeroed memory is not
 * enough because the format must be known before the first resize. */
fc_render_target fc_render_target_init(GLenum color_format, bool with_depth, bool linear);

/* Makes width x height the image in use, growing the attachments (to the
 * larger of their size and the request, per axis) only when it does not fit.
 * Passes that read the colour texture must stay inside width x height: the
 * texels beyond hold earlier, larger images. FC_ERR_GL when the framebuffer
 * is incomplete, FC_ERR_RENDER when the GPU runs out of memory. */
fc_code fc_render_target_resize(fc_render_target *t, uint32_t width, uint32_t height, fc_error *err);

/* Binds the framebuffer for drawing and sets the viewport to the image in use. */
void fc_render_target_bind(const fc_render_target *t);

/* fc_render_target_bind for sprites drawn over what the target holds (the
 * spray's droplets, the foam's discs): hidden behind its depth, writing
 * none, blended "over" its colour without touching its alpha, and encoded
 * to sRGB where the target stores sRGB. */
void fc_render_target_bind_overlay(const fc_render_target *t);

/* Frees the attachments; the next resize allocates them at its size. */
void fc_render_target_release(fc_render_target *t);

/* Sets an ivec2 uniform of `program` to the image in use (the bound that
 * texelFetch clamps to, where textureSize would include stale texels). */
void fc_render_target_uniform_size(GLuint program, GLint location, const fc_render_target *t);

/* Adds the target's bytes and allocations to m's render targets. */
void fc_render_target_tally(const fc_render_target *t, fc_gpu_memory *m);

#endif
