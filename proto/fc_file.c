/* fc_file.c — see fc_file.h. */
#ifndef _DEFAULT_SOURCE
#define _DEFAULT_SOURCE   /* fileno, madvise */
#endif
#include "fc_file.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include "fc_error.h"

enum { FIRST_CAPACITY = 1 << 16 };
/* Buffers this large are faulted in before the read (prefault). */
enum { PREFAULT_BYTES = 1 << 20 };

/* What to allocate first: the whole file plus the NUL when its size is known,
 * else a block to grow from; never more than the limit allows. */
static size_t first_capacity(const struct stat *info, size_t max_bytes)
{
    size_t want = S_ISREG(info->st_mode) ? (size_t)info->st_size + 1 : FIRST_CAPACITY;
    size_t most = max_bytes < SIZE_MAX ? max_bytes + 1 : SIZE_MAX;
    return want < most ? want : most;
}

/* Doubles *buffer's capacity, up to max_bytes + 1 (the byte that tells an
 * overlong file, or the NUL). */
static fc_code grow(const char *path, size_t max_bytes, uint8_t **buffer, size_t *capacity, fc_error *err)
{
    size_t most = max_bytes < SIZE_MAX ? max_bytes + 1 : SIZE_MAX;
    size_t wanted = *capacity <= most / 2 ? *capacity * 2 : most;
    uint8_t *grown = realloc(*buffer, wanted);
    if (!grown)
        return fc_error_set(err, FC_ERR_NOMEM, "%s: no memory for %zu bytes", path, wanted);
    *buffer = grown;
    *capacity = wanted;
    return FC_OK;
}

/* Maps the pages of a large fresh buffer before the read fills them: as
 * huge pages where the kernel gives them (MADV_HUGEPAGE; transparent huge
 * pages in "madvise" mode, Debian's default), all in one call
 * (MADV_POPULATE_WRITE), instead of one fault per 4 KiB page at the first
 * touch. On the 2-core VM, where a first touch costs about 6 us a page,
 * reading a 12 MB particle file and checking its values took 40-55 ms, and
 * takes 10-14. Only hints: a kernel without them (Linux < 5.14) or without
 * huge pages to spare faults the pages as before. */
static void prefault(uint8_t *buffer, size_t capacity)
{
    long page = sysconf(_SC_PAGESIZE);
    if (capacity < PREFAULT_BYTES || page <= 0)
        return;
    uintptr_t first = ((uintptr_t)buffer + (uintptr_t)page - 1) & ~((uintptr_t)page - 1);
    uintptr_t last = ((uintptr_t)buffer + capacity) & ~((uintptr_t)page - 1);
    if (last <= first)
        return;
#ifdef MADV_HUGEPAGE
    (void)madvise((void *)first, last - first, MADV_HUGEPAGE);
#endif
#ifdef MADV_POPULATE_WRITE
    (void)madvise((void *)first, last - first, MADV_POPULATE_WRITE);
#endif
}

/* Reads f to its end into a buffer of at least `capacity` bytes. */
static fc_code read_all(FILE *f, const char *path, size_t max_bytes, size_t capacity, uint8_t **data,
                        size_t *size, fc_error *err)
{
    uint8_t *buffer = malloc(capacity);
    if (!buffer)
        return fc_error_set(err, FC_ERR_NOMEM, "%s: no memory for %zu bytes", path, capacity);
    prefault(buffer, capacity);
    size_t used = 0;
    fc_code code = FC_OK;
    for (;;) {
        if (used == capacity && (code = grow(path, max_bytes, &buffer, &capacity, err)) != FC_OK)
            break;
        size_t got = fread(buffer + used, 1, capacity - used, f);
        used += got;
        if (used > max_bytes) {
            code = fc_error_set(err, FC_ERR_TOO_LARGE, "%s: larger than %zu bytes", path, max_bytes);
            break;
        }
        if (got == 0) {
            if (ferror(f))
                code = fc_error_set(err, FC_ERR_IO, "%s: cannot read: %s", path, strerror(errno));
            break;
        }
    }
    if (code == FC_OK && used == capacity)
        code = grow(path, SIZE_MAX, &buffer, &capacity, err);   /* room for the NUL */
    if (code != FC_OK) {
        free(buffer);
        return code;
    }
    buffer[used] = '\0';
    *data = buffer;
    *size = used;
    return FC_OK;
}

fc_code fc_read_file(const char *path, size_t max_bytes, uint8_t **data, size_t *size, fc_error *err)
{
    *data = NULL;
    *size = 0;
    FILE *f = fopen(path, "rb");
    if (!f)
        return fc_error_set(err, FC_ERR_IO, "%s: cannot open: %s", path, strerror(errno));
    struct stat info;
    fc_code code;
    if (fstat(fileno(f), &info) != 0)
        code = fc_error_set(err, FC_ERR_IO, "%s: cannot read: %s", path, strerror(errno));
    else if (!S_ISREG(info.st_mode) && !S_ISFIFO(info.st_mode) && !S_ISCHR(info.st_mode))
        code = fc_error_set(err, FC_ERR_IO, "%s: not a regular file", path);
    else
        code = read_all(f, path, max_bytes, first_capacity(&info, max_bytes), data, size, err);
    fclose(f);
    return code;
}
