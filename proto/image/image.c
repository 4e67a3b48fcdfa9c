/* image.c — size and release of the CPU images the pipeline reads back. */
#include "image.h"

#include <stdlib.h>

static size_t bytes_per_channel(fc_pixel_type type)
{
    return type == FC_PIXEL_F32 ? sizeof(float) : 1u;
}

size_t fc_image_size(const fc_image *img)
{
    return (size_t)img->width * img->height * img->channels * bytes_per_channel(img->type);
}

void fc_image_free(fc_image *img)
{
    if (!img)
        return;
    free(img->pixels);
    *img = (fc_image){0};
}
