/* render_pictures.h — what the `fluidcast render` tests measure in an image:
 * decoded RGB8 pictures (from PNG files with OpenImageIO), where the blue
 * fluid lies over the neutral floor and sky, and how close two pictures are. */
#ifndef FC_TEST_RENDER_PICTURES_H
#define FC_TEST_RENDER_PICTURES_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

typedef struct picture {
    uint32_t width, height;
    uint8_t *rgb;    /* 3 bytes a pixel, malloc'd */
} picture;

/* The PNG file as RGB8 (grey images repeated into the three channels). */
bool read_png(const char *path, picture *out);

/* The fluid is blue over a neutral floor and sky: pixels whose blue exceeds
 * their red by 60. Returns the mean x of those pixels, -1 when none;
 * *pixels gets their number. */
double fluid_centroid_x(const uint8_t *rgb, uint32_t width, uint32_t height, uint32_t *pixels);

/* Peak signal-to-noise ratio of two byte arrays, in dB (99 when equal). */
double psnr(const uint8_t *a, const uint8_t *b, size_t bytes);

#endif
