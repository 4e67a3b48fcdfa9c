/* fc_buf.c — the growable output buffer encoders append messages to. */
#include "wire.h"

#include <stdlib.h>

void fc_buf_init(fc_buf *b)
{
    *b = (fc_buf){0};
}

void fc_buf_free(fc_buf *b)
{
    free(b->data);
    fc_buf_init(b);
}

void fc_buf_reset(fc_buf *b)
{
    b->len = 0;
    b->failed = false;
}

bool fc_buf_reserve(fc_buf *b, size_t extra)
{
    if (b->failed)
        return false;
    if (extra <= b->cap - b->len)
        return true;
    if (extra > SIZE_MAX - b->len) {
        b->failed = true;
        return false;
    }
    size_t needed = b->len + extra;
    /* Doubling keeps a sequence of appends linear overall. */
    size_t cap = b->cap ? b->cap : 256;
    while (cap < needed)
        cap = cap > SIZE_MAX / 2 ? needed : cap * 2;
    uint8_t *data = realloc(b->data, cap);
    if (!data) {
        b->failed = true;
        return false;
    }
    b->data = data;
    b->cap = cap;
    return true;
}
