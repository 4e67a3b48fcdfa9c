/* aov_coverage.c — see aov_coverage.h. */
#include "aov_coverage.h"

#include <stdlib.h>

#include "cli_runner.h"
#include "fc_error.h"
#include "support/image_decode.h"

bool *aov_coverage(const char *path, uint32_t width, uint32_t height)
{
    size_t size;
    uint8_t *data = read_whole_file(path, &size);
    fc_decoded_image img = { 0 };
    fc_error err;
    bool ok = data && fc_decode_image(data, size, "exr", 1, &img, &err) == FC_OK;
    free(data);
    bool right_size = ok && img.width == width && img.height == height;
    bool *covered = right_size ? calloc((size_t)width * height, sizeof *covered) : NULL;
    for (size_t i = 0; covered && i < (size_t)width * height; i++)
        covered[i] = ((const float *)img.pixels)[i * img.channels] > 0.0f;
    if (ok)
        fc_decoded_image_free(&img);
    return covered;
}

int coverage_difference(const bool *a, const bool *b, size_t pixels)
{
    int differ = 0;
    for (size_t i = 0; i < pixels; i++)
        differ += a[i] != b[i];
    return differ;
}
