/* scene_fixtures.h — small PNG files for the scene-image tests, written byte
 * by byte (zlib-compressed by a Python script), so their pixels are known
 * independently of any code under test. */
#ifndef FC_SCENE_FIXTURES_H
#define FC_SCENE_FIXTURES_H

#include <stddef.h>
#include <stdint.h>

extern const uint8_t png_magenta_4x4[];    /* 4x4 RGB, every pixel (200, 40, 120) */
extern const size_t png_magenta_4x4_size;
extern const uint8_t png_red_4x4[];        /* 4x4 RGB, every pixel (255, 0, 0) */
extern const size_t png_red_4x4_size;
extern const uint8_t png_blue_4x4[];       /* 4x4 RGB, every pixel (0, 0, 255) */
extern const size_t png_blue_4x4_size;
extern const uint8_t png_red_4x2[];        /* 4x2 RGB red: not square */
extern const size_t png_red_4x2_size;
extern const uint8_t png_black_8193x1[];   /* 8193x1 grey: wider than a scene image may be */
extern const size_t png_black_8193x1_size;

/* The PNG signature followed by text: not a decodable image. */
extern const uint8_t not_an_image[];
extern const size_t not_an_image_size;

#endif
