/* test_wire_scene.c — BACKGROUND and ENVIRONMENT framing (PROTOCOL.md section
 * 11): exact bytes written, decoded views into the payload, and every layout
 * error with its code. The image files themselves are opaque here. */
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "test_util.h"
#include "wire.h"
#include "wire_scene.h"

/* Decodes from an exact-size heap copy, so a read past the end leaves the allocation (ASan, valgrind). */
static fc_code read_environment_copy(const uint8_t *p, size_t n, bool *has_faces, fc_error *err)
{
    uint8_t *copy = malloc(n ? n : 1);
    memcpy(copy, p, n);
    fc_encoded_image faces[FC_CUBE_FACES];
    fc_code code = fc_wire_read_environment(copy, n, faces, has_faces, err);
    free(copy);
    return code;
}

static void test_background_bytes(void)
{
    static const uint8_t file[5] = {0x89, 'P', 'N', 'G', 0x0d};
    const uint8_t expected[] = {'F', 'C', 'S', 'T', 10, 0, 0, 0, 0x21, 0, 0, 0, 5, 0, 0, 0,
                                0x89, 'P', 'N', 'G', 0x0d};
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    fc_encoded_image image = {file, sizeof file};
    CHECK_CODE(fc_wire_write_background(&b, 0x21, &image, &err), FC_OK);
    CHECK(b.len == sizeof expected && memcmp(b.data, expected, sizeof expected) == 0);

    fc_encoded_image back;
    CHECK_CODE(fc_wire_read_background(b.data + FC_WIRE_HEADER_SIZE, 5, &back, &err), FC_OK);
    CHECK(back.data == b.data + FC_WIRE_HEADER_SIZE && back.size == 5);

    /* No image: an empty payload, read back as size 0. */
    fc_buf_reset(&b);
    CHECK_CODE(fc_wire_write_background(&b, 1, NULL, &err), FC_OK);
    CHECK(b.len == FC_WIRE_HEADER_SIZE && b.data[4] == 10 && b.data[12] == 0);
    CHECK_CODE(fc_wire_read_background(b.data, 0, &back, &err), FC_OK);
    CHECK(back.size == 0 && back.data == NULL);
    fc_buf_free(&b);
}

static void test_environment_bytes(void)
{
    static const uint8_t a[2] = {0xA1, 0xA2}, b1[1] = {0xB1};
    fc_encoded_image faces[FC_CUBE_FACES] = {{a, 2}, {b1, 1}, {a, 2}, {b1, 1}, {a, 1}, {b1, 1}};
    const uint8_t expected_payload[] = {
        2, 0, 0, 0, 0, 0, 0, 0, 0xA1, 0xA2, /* +X */
        1, 0, 0, 0, 0, 0, 0, 0, 0xB1,       /* -X */
        2, 0, 0, 0, 0, 0, 0, 0, 0xA1, 0xA2, /* +Y */
        1, 0, 0, 0, 0, 0, 0, 0, 0xB1,       /* -Y */
        1, 0, 0, 0, 0, 0, 0, 0, 0xA1,       /* +Z */
        1, 0, 0, 0, 0, 0, 0, 0, 0xB1,       /* -Z */
    };
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    CHECK_CODE(fc_wire_write_environment(&b, 3, faces, &err), FC_OK);
    CHECK(b.len == FC_WIRE_HEADER_SIZE + sizeof expected_payload);
    CHECK(b.data[4] == 11 && b.data[12] == sizeof expected_payload);
    CHECK(b.len == FC_WIRE_HEADER_SIZE + sizeof expected_payload &&
          memcmp(b.data + FC_WIRE_HEADER_SIZE, expected_payload, sizeof expected_payload) == 0);

    fc_encoded_image back[FC_CUBE_FACES];
    bool has_faces = false;
    const uint8_t *payload = b.data + FC_WIRE_HEADER_SIZE;
    CHECK_CODE(fc_wire_read_environment(payload, sizeof expected_payload, back, &has_faces, &err), FC_OK);
    CHECK(has_faces);
    CHECK(back[0].data == payload + 8 && back[0].size == 2);
    CHECK(back[1].data == payload + 18 && back[1].size == 1);
    CHECK(back[5].data == payload + sizeof expected_payload - 1 && back[5].size == 1);

    /* No cube map: an empty payload. */
    fc_buf_reset(&b);
    CHECK_CODE(fc_wire_write_environment(&b, 4, NULL, &err), FC_OK);
    CHECK(b.len == FC_WIRE_HEADER_SIZE && b.data[12] == 0);
    CHECK_CODE(fc_wire_read_environment(payload, 0, back, &has_faces, &err), FC_OK);
    CHECK(!has_faces);

    /* An empty face is refused before anything is written. */
    faces[3].size = 0;
    fc_buf_reset(&b);
    CHECK_CODE(fc_wire_write_environment(&b, 5, faces, &err), FC_ERR_INVALID_VALUE);
    CHECK_MSG(strstr(err.message, "-Y") != NULL, "%s", err.message);
    CHECK(b.len == 0);
    fc_buf_free(&b);
}

/* Six faces of one byte each: 6 x (8 + 1) bytes. */
static size_t six_faces(uint8_t out[64])
{
    size_t n = 0;
    for (int i = 0; i < FC_CUBE_FACES; i++) {
        memset(out + n, 0, 8);
        out[n] = 1;
        out[n + 8] = (uint8_t)(0xF0 + i);
        n += 9;
    }
    return n;
}

static void test_environment_rejections(void)
{
    uint8_t p[64];
    size_t n = six_faces(p);
    bool has_faces;
    fc_error err;
    CHECK_CODE(read_environment_copy(p, n, &has_faces, &err), FC_OK);
    /* Five faces only, a face cut short, a length field cut short. */
    CHECK_CODE(read_environment_copy(p, n - 9, &has_faces, &err), FC_ERR_MALFORMED);
    CHECK_CODE(read_environment_copy(p, n - 1, &has_faces, &err), FC_ERR_MALFORMED);
    CHECK_CODE(read_environment_copy(p, 4, &has_faces, &err), FC_ERR_MALFORMED);
    /* A byte after the sixth face. */
    p[n] = 0;
    CHECK_CODE(read_environment_copy(p, n + 1, &has_faces, &err), FC_ERR_MALFORMED);
    /* A length far past the payload, including one that would wrap a size_t. */
    n = six_faces(p);
    p[7] = 0x80;
    CHECK_CODE(read_environment_copy(p, n, &has_faces, &err), FC_ERR_MALFORMED);
    n = six_faces(p);
    p[9 * 2] = 200;
    CHECK_CODE(read_environment_copy(p, n, &has_faces, &err), FC_ERR_MALFORMED);
    /* A well-framed payload whose -Y face has 0 bytes: a value error, not a layout one. */
    uint8_t empty_face[64];
    size_t m = 0;
    for (int i = 0; i < FC_CUBE_FACES; i++) {
        uint8_t size = i == 3 ? 0 : 1;
        memset(empty_face + m, 0, 8);
        empty_face[m] = size;
        m += 8;
        if (size)
            empty_face[m++] = (uint8_t)i;
    }
    CHECK_CODE(read_environment_copy(empty_face, m, &has_faces, &err), FC_ERR_INVALID_VALUE);
    CHECK_MSG(strstr(err.message, "-Y") != NULL, "%s", err.message);
}

int main(void)
{
    test_background_bytes();
    test_environment_bytes();
    test_environment_rejections();
    return test_result();
}
