/* fuzz_reader.c — libFuzzer target for one particle file format, chosen at
 * build time (FUZZ_FORMAT, FUZZ_FILE_NAME): the input is the whole file.
 *
 * Beyond memory safety it checks the reader contract of particle_reader.h:
 * a refusal is FC_ERR_PARSE (or NOMEM) naming the file and leaves no frame
 * behind; an accepted file gives a non-empty frame of finite values. */
#include <stdint.h>
#include <string.h>

#include "fc_frame.h"
#include "fuzz_check.h"
#include "particle_reader.h"

#ifndef FUZZ_FORMAT
#error "FUZZ_FORMAT must name the fc_file_format under test"
#endif

static void check_refusal(fc_code code, const fc_error *err, const fc_frame *frame)
{
    fuzz_require_reported(code, err);
    FUZZ_REQUIRE(code == FC_ERR_PARSE || code == FC_ERR_NOMEM, "unexpected code %d: %s", (int)code, err->message);
    FUZZ_REQUIRE(strncmp(err->message, FUZZ_FILE_NAME ":", strlen(FUZZ_FILE_NAME ":")) == 0,
                 "message does not name the file: %s", err->message);
    FUZZ_REQUIRE(frame->count == 0 && !frame->positions && !frame->density && !frame->velocity && !frame->ids,
                 "a refused file left a partial frame (%llu particles)", (unsigned long long)frame->count);
}

/* Raw .f32 files are the positions themselves, so the frame must hold exactly those bytes. */
static void check_f32_positions(const fc_frame *frame, const uint8_t *data, size_t size)
{
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    FUZZ_REQUIRE(frame->count * 12 == size, "%llu particles from %zu bytes", (unsigned long long)frame->count, size);
    FUZZ_REQUIRE(memcmp(frame->positions, data, size) == 0, "positions differ from the file's floats");
#else
    (void)frame, (void)data, (void)size;
#endif
}

static void check_frame(const fc_frame *frame, const uint8_t *data, size_t size)
{
    fc_error err = {FC_OK, ""};
    FUZZ_REQUIRE(frame->count > 0 && frame->positions != NULL, "accepted file without particles");
    /* Every particle takes at least one byte of the file; a gzip'd BGEO's at least 16 bytes, a compressed
     * VTK XML or HDF5 file's 3 (Int8 points) of what deflate (at most 1032:1) packed into the file. */
    uint64_t most = FUZZ_FORMAT == FC_FILE_BGEO      ? (uint64_t)size * 1032 / 16 + 1
                    : FUZZ_FORMAT == FC_FILE_VTK_XML || FUZZ_FORMAT == FC_FILE_HDF5 ? (uint64_t)size * 1032 / 3 + 1
                                                     : (uint64_t)size;
    FUZZ_REQUIRE(frame->count <= most, "%llu particles from %zu bytes", (unsigned long long)frame->count, size);
    FUZZ_REQUIRE(fc_frame_validate(frame, &err) == FC_OK, "accepted frame is invalid: %s", err.message);
    if (FUZZ_FORMAT == FC_FILE_F32)
        check_f32_positions(frame, data, size);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fc_frame frame;
    fc_error err = {FC_OK, ""};
    fc_code code = fc_read_particles_mem(data, size, FUZZ_FORMAT, FUZZ_FILE_NAME, &frame, &err);
    if (code == FC_OK)
        check_frame(&frame, data, size);
    else
        check_refusal(code, &err, &frame);
    fc_frame_free(&frame);
    return 0;
}
