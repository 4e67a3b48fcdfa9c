/* bench_output.c — the benchmark's file outputs. */
#include "bench_output.h"

#include <errno.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "fc_error.h"

static fc_code write_all(FILE *f, const void *data, size_t size, const char *path, fc_error *err)
{
    if (fwrite(data, 1, size, f) != size)
        return fc_error_set(err, FC_ERR_IO, "%s: write failed: %s", path, strerror(errno));
    return FC_OK;
}

static fc_code close_output(FILE *f, fc_code rc, const char *path, fc_error *err)
{
    /* buffered data reaches the disk at fclose: its failure is a write failure */
    if (fclose(f) != 0 && rc == FC_OK)
        return fc_error_set(err, FC_ERR_IO, "%s: write failed: %s", path, strerror(errno));
    return rc;
}

/* Byte order is fixed by the format, not by the host. */
static void store_f32_le(uint8_t out[4], float v)
{
    uint32_t bits;
    memcpy(&bits, &v, sizeof bits);
    for (int i = 0; i < 4; i++)
        out[i] = (uint8_t)(bits >> (8 * i));
}

fc_code bench_write_scene_f32(const fc_frame *frame, const char *path, fc_error *err)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return fc_error_set(err, FC_ERR_IO, "%s: cannot create: %s", path, strerror(errno));
    uint8_t chunk[3 * 4 * 1024];
    const uint64_t n = 3 * frame->count;
    fc_code rc = FC_OK;
    for (uint64_t done = 0; rc == FC_OK && done < n;) {
        size_t used = 0;
        for (; done < n && used < sizeof chunk; done++, used += 4)
            store_f32_le(chunk + used, frame->positions[done]);
        rc = write_all(f, chunk, used, path, err);
    }
    return close_output(f, rc, path, err);
}

fc_code bench_write_bytes(const void *data, size_t size, const char *path, fc_error *err)
{
    FILE *f = fopen(path, "wb");
    if (!f)
        return fc_error_set(err, FC_ERR_IO, "%s: cannot create: %s", path, strerror(errno));
    return close_output(f, write_all(f, data, size, path, err), path, err);
}
