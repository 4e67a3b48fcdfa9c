/* render_pictures.c — see render_pictures.h. */
#include "render_pictures.h"

#include <math.h>
#include <stdlib.h>

#include "cli_runner.h"
#include "fc_error.h"
#include "support/image_decode.h"

bool read_png(const char *path, picture *out)
{
    size_t size;
    uint8_t *data = read_whole_file(path, &size);
    fc_decoded_image img;
    fc_error err;
    bool ok = data && fc_decode_image(data, size, "png", 0, &img, &err) == FC_OK;
    free(data);
    if (!ok)
        return false;
    out->width = img.width;
    out->height = img.height;
    out->rgb = malloc((size_t)img.width * img.height * 3);
    if (!out->rgb) {
        fc_decoded_image_free(&img);
        return false;
    }
    const uint8_t *src = img.pixels;
    for (size_t p = 0; p < (size_t)img.width * img.height; p++)
        for (int c = 0; c < 3; c++)
            out->rgb[3 * p + c] = src[p * img.channels + (c < (int)img.channels ? c : 0)];
    fc_decoded_image_free(&img);
    return true;
}

double fluid_centroid_x(const uint8_t *rgb, uint32_t width, uint32_t height, uint32_t *pixels)
{
    double sum = 0;
    *pixels = 0;
    for (uint32_t y = 0; y < height; y++)
        for (uint32_t x = 0; x < width; x++) {
            const uint8_t *p = rgb + 3 * ((size_t)y * width + x);
            if (p[2] > p[0] + 60) {
                sum += x;
                (*pixels)++;
            }
        }
    return *pixels ? sum / *pixels : -1.0;
}

double psnr(const uint8_t *a, const uint8_t *b, size_t bytes)
{
    double se = 0;
    for (size_t i = 0; i < bytes; i++) {
        double d = (double)a[i] - b[i];
        se += d * d;
    }
    double mse = se / (double)bytes;
    return mse > 0 ? 10.0 * log10(255.0 * 255.0 / mse) : 99.0;
}
