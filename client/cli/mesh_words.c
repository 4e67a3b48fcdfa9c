/* mesh_words.c — see mesh_words.h. */
#include "mesh_words.h"

#include <stdint.h>
#include <string.h>

bool fc_mesh_put_words(FILE *to, const void *words, size_t count)
{
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    return fwrite(words, 4, count, to) == count;
#else
    const uint8_t *p = words;
    for (size_t i = 0; i < count; i++) {
        uint32_t w;
        memcpy(&w, p + 4 * i, 4);
        uint8_t le[4] = {(uint8_t)w, (uint8_t)(w >> 8), (uint8_t)(w >> 16), (uint8_t)(w >> 24)};
        if (fwrite(le, 1, 4, to) != 4)
            return false;
    }
    return true;
#endif
}
