/* gl_util.h — the GL plumbing every pass shares: error checks that become
 * fc_code values, and float/colour textures with fixed sampling state. */
#ifndef FC_GL_UTIL_H
#define FC_GL_UTIL_H

#include <epoxy/gl.h>
#include <stdbool.h>
#include <stdint.h>

#include "fluidcast_types.h"

/* Drains the GL error queue after `what`: FC_OK when it was empty,
 * FC_ERR_RENDER for GL_OUT_OF_MEMORY (the request was too big for the GPU),
 * FC_ERR_GL naming the first error otherwise. */
fc_code fc_gl_check(const char *what, fc_error *err);

/* For a call that reported failure by its result (a NULL mapping, a failed
 * wait): the GL error it left, else FC_ERR_RENDER "<what> failed". */
fc_code fc_gl_failure(const char *what, fc_error *err);

/* Blocks until the GPU has run every command issued so far (a fence the
 * caller waits on); `what` names the wait in the error. */
fc_code fc_gl_wait_until_done(const char *what, fc_error *err);

/* A width x height 2D texture with immutable storage of `internal_format`,
 * clamped at the edges; `linear` chooses bilinear over nearest sampling. */
fc_code fc_gl_texture_create(GLenum internal_format, uint32_t width, uint32_t height, bool linear,
                             GLuint *texture, fc_error *err);

/* n, or the next extent above it that is not a power of two (0 stays 0).
 * llvmpipe compiles a shader variant per combination of whether each bound
 * texture's extents (a buffer's: its bytes) are powers of two, at the first
 * draw that meets it: textures and texture buffers whose extents never are
 * one meet the variants the pipeline's warm-up compiled, at any image size
 * and particle count, where a 1024-pixel-wide image compiled new ones (tens
 * of milliseconds per program, bench/RESULTS.md). One texel more costs a GPU
 * nothing. */
uint64_t fc_gl_non_pot(uint64_t n);

/* The extent a texture that only grows takes when `asked` meets its
 * `allocated` one: the larger, never a power of two (fc_gl_non_pot). */
uint32_t fc_gl_grown_extent(uint32_t asked, uint32_t allocated);

/* Bytes per texel of the sized internal formats the pipeline allocates
 * (colour, compute images, depth/stencil); 0 for any other format. */
uint32_t fc_gl_texel_bytes(GLenum internal_format);

/* A sampler object that samples nearest and clamps to the edge, whatever
 * the texture's own state: bound to a unit, a lookup at a texel's centre
 * returns that texel exactly. */
GLuint fc_gl_nearest_sampler(void);

/* Whether the current context renders on the CPU (Mesa's llvmpipe or
 * softpipe, by GL_RENDERER), where shading costs what its instructions do. */
bool fc_gl_software_rasterizer(void);

/* Draws the triangle of fullscreen.vert.glsl with the current program; core
 * profile needs a vertex array bound even when no attribute is read. */
void fc_gl_draw_fullscreen(GLuint empty_vertex_array);

/* Runs the current compute program over a width x height image, each
 * workgroup covering group_width x group_height pixels, then makes its image
 * stores visible to what reads them next: texture fetches (the next pass)
 * and framebuffer reads (the readback of an image straight from it). */
void fc_gl_dispatch_over_image(uint32_t width, uint32_t height, uint32_t group_width, uint32_t group_height);

#endif
