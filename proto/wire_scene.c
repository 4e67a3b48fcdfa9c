/* wire_scene.c — BACKGROUND and ENVIRONMENT: encoded image files framed into
 * a payload (wire_scene.h). An empty payload means "back to the built-in scene". */
#include "wire_scene.h"

#include "fc_error.h"
#include "wire_io.h"

#define FACE_LENGTH_SIZE 8u

const char *fc_cube_face_name(int face)
{
    static const char *const names[FC_CUBE_FACES] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};
    return face >= 0 && face < FC_CUBE_FACES ? names[face] : "?";
}

fc_code fc_wire_write_background(fc_buf *out, uint32_t request_id, const fc_encoded_image *image, fc_error *err)
{
    uint64_t size = image ? image->size : 0;
    fc_code code = wire_check_length(0, size, 1, "BACKGROUND", err);
    if (code != FC_OK)
        return code;
    size_t start = wire_begin_message(out, FC_MSG_BACKGROUND, request_id, (uint32_t)size);
    if (size > 0)
        wire_put_bytes(out, image->data, (size_t)size);
    return wire_end_message(out, start, err);
}

/* Payload bytes of six faces; FC_ERR_TOO_LARGE past the u32 length field. */
static fc_code environment_length(const fc_encoded_image *faces, uint32_t *length, fc_error *err)
{
    uint64_t total = 0;
    for (int i = 0; i < FC_CUBE_FACES; i++) {
        if (faces[i].size == 0)
            return fc_error_set(err, FC_ERR_INVALID_VALUE, "ENVIRONMENT: face %s is empty", fc_cube_face_name(i));
        fc_code code = wire_check_length(total + FACE_LENGTH_SIZE, faces[i].size, 1, "ENVIRONMENT", err);
        if (code != FC_OK)
            return code;
        total += FACE_LENGTH_SIZE + faces[i].size;
    }
    *length = (uint32_t)total;
    return FC_OK;
}

fc_code fc_wire_write_environment(fc_buf *out, uint32_t request_id, const fc_encoded_image *faces, fc_error *err)
{
    uint32_t length = 0;
    if (faces) {
        fc_code code = environment_length(faces, &length, err);
        if (code != FC_OK)
            return code;
    }
    size_t start = wire_begin_message(out, FC_MSG_ENVIRONMENT, request_id, length);
    for (int i = 0; faces && i < FC_CUBE_FACES; i++) {
        wire_put_u64(out, faces[i].size);
        wire_put_bytes(out, faces[i].data, (size_t)faces[i].size);
    }
    return wire_end_message(out, start, err);
}

fc_code fc_wire_read_background(const uint8_t *p, size_t n, fc_encoded_image *image, fc_error *err)
{
    (void)err;   /* any payload frames one file (or none); the decoder judges its bytes */
    image->data = n > 0 ? p : NULL;
    image->size = n;
    return FC_OK;
}

fc_code fc_wire_read_environment(const uint8_t *p, size_t n, fc_encoded_image faces[FC_CUBE_FACES], bool *has_faces,
                                 fc_error *err)
{
    *has_faces = false;
    if (n == 0)
        return FC_OK;
    fc_encoded_image read[FC_CUBE_FACES] = {{0}};
    wire_reader r = wire_reader_start(p, n, "ENVIRONMENT", err);
    for (int i = 0; i < FC_CUBE_FACES && r.code == FC_OK; i++) {
        uint64_t size = wire_get_u64(&r, "face length");
        if (r.code == FC_OK && size > wire_remaining(&r))
            wire_fail(&r, FC_ERR_MALFORMED, "face %s of %llu bytes runs past the payload (%zu bytes left)",
                      fc_cube_face_name(i), (unsigned long long)size, wire_remaining(&r));
        read[i].data = wire_get_bytes(&r, (size_t)size, "face");
        read[i].size = size;
    }
    wire_expect_end(&r);
    if (r.code != FC_OK)
        return r.code;
    for (int i = 0; i < FC_CUBE_FACES; i++) {
        if (read[i].size == 0)
            return fc_error_set(err, FC_ERR_INVALID_VALUE, "ENVIRONMENT: face %s is empty", fc_cube_face_name(i));
        faces[i] = read[i];
    }
    *has_faces = true;
    return FC_OK;
}
