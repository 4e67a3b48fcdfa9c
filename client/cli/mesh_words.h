/* mesh_words.h — what the binary mesh writers (mesh_write_*.c) share: 32-bit
 * words written in the little-endian order PLY, STL and the .vtp appended data use. */
#ifndef FC_MESH_WORDS_H
#define FC_MESH_WORDS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

/* `count` 32-bit words (floats or integers) little-endian. False when the write failed. */
bool fc_mesh_put_words(FILE *to, const void *words, size_t count);

#endif
