/* readback.c — glReadPixels into fc_image with rows flipped to top-down. */
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

static void swap_bytes(unsigned char *a, unsigned char *b, size_t n)
{
    unsigned char chunk[256];
    while (n > 0) {
        size_t step = n < sizeof chunk ? n : sizeof chunk;
        memcpy(chunk, a, step);
        memcpy(a, b, step);
        memcpy(b, chunk, step);
        a += step;
        b += step;
        n -= step;
    }
}

static void flip_rows(fc_image *img)
{
    size_t stride = fc_image_size(img) / img->height;
    unsigned char *pixels = img->pixels;
    for (uint32_t top = 0, bottom = img->height - 1; top < bottom; top++, bottom--)
        swap_bytes(pixels + top * stride, pixels + bottom * stride, stride);
}

fc_code fc_readback(const fc_render_target *target, uint32_t channels, fc_pixel_type type, fc_image *out,
                    fc_error *err)
{
    out->width = target->width;
    out->height = target->height;
    out->channels = channels;
    out->type = type;
    size_t bytes = fc_image_size(out);
    fc_code code = reserve(out, bytes, err);
    if (code != FC_OK)
        return code;
    glBindFramebuffer(GL_READ_FRAMEBUFFER, target->framebuffer);
    glNamedFramebufferReadBuffer(target->framebuffer, GL_COLOR_ATTACHMENT0);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    GLenum format = channels == 1 ? GL_RED : channels == 3 ? GL_RGB : GL_RGBA;
    GLenum gl_type = type == FC_PIXEL_F32 ? GL_FLOAT : GL_UNSIGNED_BYTE;
    glReadPixels(0, 0, (GLsizei)out->width, (GLsizei)out->height, format, gl_type, out->pixels);
    code = fc_gl_check("reading back the image", err);
    if (code == FC_OK)
        flip_rows(out);
    return code;
}
