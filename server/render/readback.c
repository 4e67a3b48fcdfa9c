/* readback.c — glReadPixels into a persistently mapped pixel-pack buffer,
 * then rows copied out top-down. */
#include "readback.h"

#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "gl_util.h"

static fc_code reserve(fc_image *img, size_t bytes, fc_error *err)
{
    if (bytes <= img->capacity)
        return FC_OK;
    void *pixels = realloc(img->pixels, bytes);
    if (!pixels)
        return fc_error_set(err, FC_ERR_NOMEM, "out of memory for a %ux%u image (%zu bytes)", img->width,
                            img->height, bytes);
    img->pixels = pixels;
    img->capacity = bytes;
    return FC_OK;
}

fc_readback fc_readback_init(void)
{
    return (fc_readback){0};
}

/* Drops the pack buffer, keeping the count of allocations. */
static void release_pack_buffer(fc_readback *r)
{
    if (r->mapped)
        glUnmapNamedBuffer(r->pack_buffer);
    glDeleteBuffers(1, &r->pack_buffer);
    r->pack_buffer = 0;
    r->mapped = NULL;
    r->capacity = 0;
}

void fc_readback_release(fc_readback *r)
{
    release_pack_buffer(r);
    *r = fc_readback_init();
}

/* A pack buffer of at least `bytes`, mapped for reading as long as it lives. */
static fc_code reserve_pack_buffer(fc_readback *r, size_t bytes, fc_error *err)
{
    if (bytes <= r->capacity)
        return FC_OK;
    release_pack_buffer(r);
    r->allocations++;
    GLbitfield flags = GL_MAP_READ_BIT | GL_MAP_PERSISTENT_BIT | GL_MAP_COHERENT_BIT;
    glCreateBuffers(1, &r->pack_buffer);
    glNamedBufferStorage(r->pack_buffer, (GLsizeiptr)bytes, NULL, flags);
    fc_code code = fc_gl_check("allocating the readback buffer", err);
    if (code == FC_OK && !(r->mapped = glMapNamedBufferRange(r->pack_buffer, 0, (GLsizeiptr)bytes, flags)))
        code = fc_gl_failure("mapping the readback buffer", err);
    if (code != FC_OK) {
        release_pack_buffer(r);
        return code;
    }
    r->capacity = bytes;
    return FC_OK;
}

/* Starts the copy of the target into the pack buffer and waits until it is there. */
static fc_code read_into_pack_buffer(const fc_readback *r, const fc_render_target *target, uint32_t channels,
                                     fc_pixel_type type, fc_error *err)
{
    glBindFramebuffer(GL_READ_FRAMEBUFFER, target->framebuffer);
    glNamedFramebufferReadBuffer(target->framebuffer, GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, r->pack_buffer);
    GLenum format = channels == 1 ? GL_RED : channels == 3 ? GL_RGB : GL_RGBA;
    GLenum gl_type = type == FC_PIXEL_F32 ? GL_FLOAT : GL_UNSIGNED_BYTE;
    glReadPixels(0, 0, (GLsizei)target->width, (GLsizei)target->height, format, gl_type, NULL);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    fc_code code = fc_gl_check("reading back the image", err);
    return code == FC_OK ? fc_gl_wait_until_done("waiting for the readback", err) : code;
}

fc_code fc_readback_run(fc_readback *r, const fc_render_target *target, uint32_t channels, fc_pixel_type type,
                        fc_image *out, fc_error *err)
{
    out->width = target->width;
    out->height = target->height;
    out->channels = channels;
    out->type = type;
    size_t bytes = fc_image_size(out);
    fc_code code = reserve(out, bytes, err);
    if (code == FC_OK)
        code = reserve_pack_buffer(r, bytes, err);
    if (code == FC_OK)
        code = read_into_pack_buffer(r, target, channels, type, err);
    if (code != FC_OK)
        return code;
    size_t stride = bytes / out->height;
    unsigned char *rows = out->pixels;
    for (uint32_t y = 0; y < out->height; y++)
        memcpy(rows + (size_t)(out->height - 1 - y) * stride, r->mapped + (size_t)y * stride, stride);
    return FC_OK;
}

void fc_readback_tally(const fc_readback *r, fc_gpu_memory *m)
{
    m->readback_bytes += r->capacity;
    m->allocations += r->allocations;
}
