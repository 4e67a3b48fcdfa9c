/* image.h — a CPU image as the render pipeline reads it back and the encoder consumes it. */
#ifndef FC_IMAGE_H
#define FC_IMAGE_H

#include <stddef.h>
#include <stdint.h>

typedef enum fc_pixel_type {
    FC_PIXEL_U8 = 1,     /* 8-bit, sRGB-encoded colour (display-ready) */
    FC_PIXEL_F32 = 2     /* 32-bit float, linear */
} fc_pixel_type;

/* Rows run top to bottom, tightly packed: row stride = width * channels * bytes per channel. */
typedef struct fc_image {
    uint32_t width;
    uint32_t height;
    uint32_t channels;   /* 1 (AOVs), 3 (the normal AOV, xyz) or 4 (RGBA colour) */
    fc_pixel_type type;
    void *pixels;        /* owned; fc_image_free releases it */
    size_t capacity;     /* bytes allocated, so a reused image does not reallocate */
} fc_image;

/* Bytes of pixel data for the current width/height/channels/type. */
size_t fc_image_size(const fc_image *img);
void fc_image_free(fc_image *img);

#endif
