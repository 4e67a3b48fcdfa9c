/* test_wire_roundtrip.c — every message survives encode -> decode unchanged,
 * and the byte layout matches PROTOCOL.md exactly (hand-written expected bytes). */
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "test_util.h"
#include "wire.h"

#define NO_LIMIT UINT32_MAX

/* Checks b holds exactly one message of `type` and `request_id`; returns its payload. */
static const uint8_t *single_payload(const fc_buf *b, fc_msg_type type, uint32_t request_id, size_t *n)
{
    fc_msg_header h;
    fc_error err;
    *n = 0;
    if (b->len < FC_WIRE_HEADER_SIZE) {
        CHECK_MSG(0, "buffer of %zu bytes holds no header", b->len);
        return NULL;
    }
    CHECK_CODE(fc_wire_decode_header(b->data, NO_LIMIT, &h, &err), FC_OK);
    CHECK(h.type == type);
    CHECK(h.flags == 0);
    CHECK(h.request_id == request_id);
    CHECK_MSG(h.length == b->len - FC_WIRE_HEADER_SIZE, "header length %u, payload %zu", h.length,
              b->len - FC_WIRE_HEADER_SIZE);
    *n = b->len - FC_WIRE_HEADER_SIZE;
    return b->data + FC_WIRE_HEADER_SIZE;
}

static void test_header_bytes(void)
{
    const uint8_t expected[16] = {'F', 'C', 'S', 'T', 0x03, 0x00, 0x00, 0x00,
                                  0x04, 0x03, 0x02, 0x01, 0x20, 0x01, 0x00, 0x00};
    fc_msg_header h = {.type = FC_MSG_FRAME, .flags = 0, .request_id = 0x01020304, .length = 0x120};
    uint8_t out[16];
    fc_wire_encode_header(out, &h);
    CHECK(memcmp(out, expected, sizeof expected) == 0);

    fc_msg_header back;
    fc_error err;
    CHECK_CODE(fc_wire_decode_header(expected, 0x120, &back, &err), FC_OK);
    CHECK(back.type == FC_MSG_FRAME && back.flags == 0 && back.request_id == 0x01020304 && back.length == 0x120);
}

static void test_frame_bytes(void)
{
    /* Two particles with density: positions (1,2,3) and (-1,0.5,0), density 1000 and 0.25. */
    const uint8_t expected[] = {
        'F', 'C', 'S', 'T', 0x03, 0x00, 0x00, 0x00, 0x07, 0x00, 0x00, 0x00, 0x30, 0x00, 0x00, 0x00, /* header */
        0x02, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, /* count 2 */
        0x01, 0x00, 0x00, 0x00,                         /* attributes: density */
        0x00, 0x00, 0x00, 0x00,                         /* reserved */
        0x00, 0x00, 0x80, 0x3F, 0x00, 0x00, 0x00, 0x40, 0x00, 0x00, 0x40, 0x40, /* 1 2 3 */
        0x00, 0x00, 0x80, 0xBF, 0x00, 0x00, 0x00, 0x3F, 0x00, 0x00, 0x00, 0x00, /* -1 0.5 0 */
        0x00, 0x00, 0x7A, 0x44, 0x00, 0x00, 0x80, 0x3E,                         /* 1000 0.25 */
    };
    float positions[6] = {1, 2, 3, -1, 0.5f, 0};
    float density[2] = {1000, 0.25f};
    fc_frame frame = {.count = 2, .positions = positions, .density = density};
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    CHECK_CODE(fc_wire_write_frame(&b, 7, &frame, &err), FC_OK);
    CHECK_MSG(b.len == sizeof expected, "%zu bytes, expected %zu", b.len, sizeof expected);
    CHECK(b.len == sizeof expected && memcmp(b.data, expected, sizeof expected) == 0);
    fc_buf_free(&b);
}

/* PROTOCOL.md 7.3's second example: ids and radii (bit 3) after the positions,
 * in the order of the attribute table; the radii are f32 like the positions. */
static void test_frame_radius_bytes(void)
{
    const uint8_t expected[] = {
        'F', 'C', 'S', 'T', 0x03, 0x00, 0x00, 0x00, 0x07, 0x00, 0x00, 0x00, 0x38, 0x00, 0x00, 0x00, /* header */
        0x02, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, /* count 2 */
        0x0C, 0x00, 0x00, 0x00,                         /* attributes: ids | radius */
        0x00, 0x00, 0x00, 0x00,                         /* reserved */
        0x00, 0x00, 0x80, 0x3F, 0x00, 0x00, 0x00, 0x40, 0x00, 0x00, 0x40, 0x40, /* 1 2 3 */
        0x00, 0x00, 0x80, 0xBF, 0x00, 0x00, 0x00, 0x3F, 0x00, 0x00, 0x00, 0x00, /* -1 0.5 0 */
        0x07, 0x00, 0x00, 0x00, 0x09, 0x00, 0x00, 0x00,                         /* ids 7 9 */
        0x00, 0x00, 0x00, 0x3F, 0x00, 0x00, 0x00, 0x40,                         /* radius 0.5 2 */
    };
    float positions[6] = {1, 2, 3, -1, 0.5f, 0};
    uint32_t ids[2] = {7, 9};
    float radius[2] = {0.5f, 2.0f};
    fc_frame frame = {.count = 2, .positions = positions, .ids = ids, .radius = radius};
    CHECK(fc_frame_attributes(&frame) == (FC_ATTR_IDS | FC_ATTR_RADIUS) && FC_ATTR_RADIUS == 8);
    CHECK(fc_frame_particle_bytes(FC_ATTR_ALL) == 36 && fc_frame_particle_bytes(FC_ATTR_RADIUS) == 16);
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    CHECK_CODE(fc_wire_write_frame(&b, 7, &frame, &err), FC_OK);
    CHECK_MSG(b.len == sizeof expected, "%zu bytes, expected %zu", b.len, sizeof expected);
    CHECK(b.len == sizeof expected && memcmp(b.data, expected, sizeof expected) == 0);
    fc_frame out = {0};
    CHECK_CODE(fc_wire_read_frame(expected + FC_WIRE_HEADER_SIZE, sizeof expected - FC_WIRE_HEADER_SIZE, 2, &out,
                                  &err),
               FC_OK);
    CHECK(out.radius && out.radius[0] == 0.5f && out.radius[1] == 2.0f && out.ids && out.ids[1] == 9);
    CHECK(!out.density && !out.velocity);
    fc_frame_free(&out);

    /* The parts a zero-copy sender hands to the socket: the radii stay where the caller keeps them. */
    fc_buf head;
    fc_buf_init(&head);
    fc_wire_span arrays[FC_WIRE_FRAME_ARRAYS];
    size_t count = 0;
    CHECK_CODE(fc_wire_write_frame_parts(&head, 7, &frame, arrays, &count, &err), FC_OK);
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    CHECK(count == 3 && arrays[2].data == radius && arrays[2].size == sizeof radius);
#endif
    fc_buf_free(&head);
    fc_buf_free(&b);
}

/* The same FRAME as test_frame_bytes as parts: the head in the buffer, the
 * arrays left where the frame keeps them, together the same bytes. */
static void test_frame_parts(void)
{
    float positions[6] = {1, 2, 3, -1, 0.5f, 0};
    float density[2] = {1000, 0.25f};
    fc_frame frame = {.count = 2, .positions = positions, .density = density};
    fc_buf head, whole;
    fc_buf_init(&head);
    fc_buf_init(&whole);
    fc_error err;
    fc_wire_span arrays[FC_WIRE_FRAME_ARRAYS];
    size_t count = 99;
    CHECK_CODE(fc_wire_write_frame_parts(&head, 7, &frame, arrays, &count, &err), FC_OK);
    CHECK_CODE(fc_wire_write_frame(&whole, 7, &frame, &err), FC_OK);
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    CHECK_MSG(count == 2 && head.len == FC_WIRE_HEADER_SIZE + 16, "%zu arrays after %zu bytes", count, head.len);
    CHECK(count == 2 && arrays[0].data == positions && arrays[0].size == sizeof positions);
    CHECK(count == 2 && arrays[1].data == density && arrays[1].size == sizeof density);
#endif
    for (size_t i = 0; i < count && count <= FC_WIRE_FRAME_ARRAYS; i++) {
        CHECK(fc_buf_reserve(&head, arrays[i].size));
        memcpy(head.data + head.len, arrays[i].data, arrays[i].size);
        head.len += arrays[i].size;
    }
    CHECK(head.len == whole.len && memcmp(head.data, whole.data, whole.len) == 0);

    /* Refused like fc_wire_write_frame, leaving nothing behind. */
    fc_buf_reset(&head);
    fc_frame empty = {.count = 0, .positions = positions};
    CHECK_CODE(fc_wire_write_frame_parts(&head, 1, &empty, arrays, &count, &err), FC_ERR_USAGE);
    CHECK(head.len == 0 && count == 0);
    fc_buf_free(&head);
    fc_buf_free(&whole);
}

static void test_hello_bytes(void)
{
    const uint8_t expected_payload[] = {
        0x01, 0x00, 0x00, 0x00, /* version_min */
        0x02, 0x00, 0x00, 0x00, /* version_max */
        0x00, 0x00, 0x00, 0x00, /* capabilities */
        0x02, 0x00, 'a', 'b',   /* client_name */
    };
    fc_hello hello = {.version_min = 1, .version_max = 2, .capabilities = 0, .client_name = "ab"};
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    CHECK_CODE(fc_wire_write_hello(&b, 1, &hello, &err), FC_OK);
    size_t n;
    const uint8_t *p = single_payload(&b, FC_MSG_HELLO, 1, &n);
    CHECK(n == sizeof expected_payload && memcmp(p, expected_payload, n) == 0);
    fc_buf_free(&b);
}

static void test_hello_roundtrip(void)
{
    fc_hello in = {.version_min = 1, .version_max = 3, .capabilities = 0x5, .client_name = "sph-solver 2.1"};
    fc_hello out;
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    CHECK_CODE(fc_wire_write_hello(&b, 11, &in, &err), FC_OK);
    size_t n;
    const uint8_t *p = single_payload(&b, FC_MSG_HELLO, 11, &n);
    CHECK_CODE(fc_wire_read_hello(p, n, &out, &err), FC_OK);
    CHECK(out.version_min == 1 && out.version_max == 3 && out.capabilities == 0x5);
    CHECK(strcmp(out.client_name, "sph-solver 2.1") == 0);
    fc_buf_free(&b);
}

static void test_welcome_roundtrip(void)
{
    fc_welcome in = {.version = 1,
                     .capabilities = 0,
                     .limits = {.max_particles = 1ull << 40, .max_width = 8192, .max_height = 4096,
                                .max_message = 1073741824u},
                     .server_version = "fluidcastd 0.1.0",
                     .renderer = "llvmpipe (LLVM 15.0.6, 256 bits)"};
    fc_welcome out;
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    CHECK_CODE(fc_wire_write_welcome(&b, 1, &in, &err), FC_OK);
    size_t n;
    const uint8_t *p = single_payload(&b, FC_MSG_WELCOME, 1, &n);
    CHECK(n == 28 + 2 + strlen(in.server_version) + 2 + strlen(in.renderer));
    CHECK_CODE(fc_wire_read_welcome(p, n, &out, &err), FC_OK);
    CHECK(out.version == 1 && out.capabilities == 0);
    CHECK(out.limits.max_particles == 1ull << 40);
    CHECK(out.limits.max_width == 8192 && out.limits.max_height == 4096 && out.limits.max_message == 1073741824u);
    CHECK(strcmp(out.server_version, in.server_version) == 0);
    CHECK(strcmp(out.renderer, in.renderer) == 0);
    fc_buf_free(&b);
}

/* Capability DEVICE: WELCOME carries `device` after `renderer`; without it
 * the layout is the original one, byte for byte (older clients read it). */
static void test_welcome_device(void)
{
    fc_welcome in = {.version = 1, .capabilities = FC_CAP_DEVICE, .limits = {16, 64, 64, 4096},
                     .server_version = "fluidcastd 0.1.0", .renderer = "NVIDIA H200/PCIe/SSE2",
                     .device = "EGL device 1, /dev/dri/renderD129, CUDA 0"};
    fc_welcome out;
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    CHECK_CODE(fc_wire_write_welcome(&b, 1, &in, &err), FC_OK);
    size_t n;
    const uint8_t *p = single_payload(&b, FC_MSG_WELCOME, 1, &n);
    size_t without = 28 + 2 + strlen(in.server_version) + 2 + strlen(in.renderer);
    CHECK(n == without + 2 + strlen(in.device));
    CHECK_CODE(fc_wire_read_welcome(p, n, &out, &err), FC_OK);
    CHECK(strcmp(out.device, in.device) == 0 && strcmp(out.renderer, in.renderer) == 0);
    /* Granted but cut off before the field: malformed, not silently empty. */
    CHECK_CODE(fc_wire_read_welcome(p, without, &out, &err), FC_ERR_MALFORMED);
    fc_buf_free(&b);

    /* Not granted: no field on the wire, whatever `device` holds; extra bytes are malformed. */
    in.capabilities = 0;
    fc_buf_init(&b);
    CHECK_CODE(fc_wire_write_welcome(&b, 1, &in, &err), FC_OK);
    p = single_payload(&b, FC_MSG_WELCOME, 1, &n);
    CHECK(n == without);
    CHECK_CODE(fc_wire_read_welcome(p, n, &out, &err), FC_OK);
    CHECK(out.device[0] == '\0');
    fc_buf_free(&b);
}

static void test_frame_roundtrip_all_attributes(void)
{
    enum { N = 5 };
    fc_frame in, out = {0};
    fc_error err;
    CHECK_CODE(fc_frame_alloc(&in, N, FC_ATTR_ALL, &err), FC_OK);
    for (int i = 0; i < N; i++) {
        for (int k = 0; k < 3; k++) {
            in.positions[3 * i + k] = 0.25f * i - k;
            in.velocity[3 * i + k] = -1.5f * k + i;
        }
        in.density[i] = 998.0f + i;
        in.ids[i] = 0xFFFFFFF0u + (uint32_t)i;
        in.radius[i] = i == 0 ? 1e6f : 0x1p-126f * (float)(i + 1); /* the largest and tiny normal radii */
    }
    fc_buf b;
    fc_buf_init(&b);
    CHECK_CODE(fc_wire_write_frame(&b, 42, &in, &err), FC_OK);
    size_t n;
    const uint8_t *p = single_payload(&b, FC_MSG_FRAME, 42, &n);
    CHECK(n == 16 + N * 36);
    CHECK_CODE(fc_wire_read_frame(p, n, N, &out, &err), FC_OK);
    CHECK(out.count == N);
    CHECK(fc_frame_attributes(&out) == FC_ATTR_ALL);
    CHECK(out.radius && memcmp(out.radius, in.radius, sizeof(float) * N) == 0);
    CHECK(out.positions && memcmp(out.positions, in.positions, sizeof(float) * 3 * N) == 0);
    CHECK(out.velocity && memcmp(out.velocity, in.velocity, sizeof(float) * 3 * N) == 0);
    CHECK(out.density && memcmp(out.density, in.density, sizeof(float) * N) == 0);
    CHECK(out.ids && memcmp(out.ids, in.ids, sizeof(uint32_t) * N) == 0);
    fc_frame_free(&in);
    fc_frame_free(&out);
    fc_buf_free(&b);
}

static void test_frame_roundtrip_each_attribute_set(void)
{
    for (uint32_t attributes = 0; attributes <= FC_ATTR_ALL; attributes++) {
        fc_frame in, out = {0};
        fc_error err;
        CHECK_CODE(fc_frame_alloc(&in, 3, attributes, &err), FC_OK);
        for (int i = 0; i < 9; i++) {
            in.positions[i] = (float)i;
            if (in.velocity)
                in.velocity[i] = -(float)i;
        }
        for (int i = 0; i < 3; i++) {
            if (in.density)
                in.density[i] = 10.0f + i;
            if (in.ids)
                in.ids[i] = 100u + (uint32_t)i;
            if (in.radius)
                in.radius[i] = 0.25f * (float)(i + 1);
        }
        fc_buf b;
        fc_buf_init(&b);
        CHECK_CODE(fc_wire_write_frame(&b, 1, &in, &err), FC_OK);
        size_t n;
        const uint8_t *p = single_payload(&b, FC_MSG_FRAME, 1, &n);
        CHECK_CODE(fc_wire_read_frame(p, n, 3, &out, &err), FC_OK);
        CHECK_MSG(fc_frame_attributes(&out) == attributes, "attributes 0x%x came back as 0x%x", attributes,
                  fc_frame_attributes(&out));
        CHECK(out.positions && out.positions[8] == 8.0f);
        if (attributes & FC_ATTR_DENSITY)
            CHECK(out.density && out.density[2] == 12.0f);
        if (attributes & FC_ATTR_VELOCITY)
            CHECK(out.velocity && out.velocity[8] == -8.0f);
        if (attributes & FC_ATTR_IDS)
            CHECK(out.ids && out.ids[2] == 102u);
        if (attributes & FC_ATTR_RADIUS)
            CHECK(out.radius && out.radius[0] == 0.25f && out.radius[2] == 0.75f);
        CHECK(n == 16 + 3 * fc_frame_particle_bytes(attributes));
        fc_frame_free(&in);
        fc_frame_free(&out);
        fc_buf_free(&b);
    }
}

static void test_camera_roundtrip(void)
{
    fc_camera in = {.eye = {1.9f, -2.6f, 1.75f}, .target = {0, 0, 0.6f}, .up = {0, 0, 1},
                    .fov_y_deg = 40, .width = 640, .height = 360};
    fc_camera out;
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    CHECK_CODE(fc_wire_write_camera(&b, 3, &in, &err), FC_OK);
    size_t n;
    const uint8_t *p = single_payload(&b, FC_MSG_CAMERA, 3, &n);
    CHECK(n == 48);
    CHECK_CODE(fc_wire_read_camera(p, n, &out, &err), FC_OK);
    CHECK(memcmp(&in, &out, sizeof in) == 0);
    fc_buf_free(&b);
}

static void test_settings_roundtrip(void)
{
    fc_settings in = {.radius = 0.028125f, .smoothing = FC_SMOOTHING_NONE, .iterations = 1000,
                      .fluid_color = {1, 0.5f, 0}, .absorption = {0, 1e6f, 3.5f}, .ior = 3.0f,
                      .filter_radius = 64, .smooth_scale = 0.5f, .refraction = 1000, .specular = 10,
                      .shininess = 1, .thickness_scale = 0.25f, .thickness_blur = 32, .noise = 10, .foam = 0,
                      .foam_tau = 1e-3f, .foam_decay = 0, .density_threshold = 1e30f,
                      .kernel = FC_KERNEL_ANISOTROPIC, .shadow = 0, .exposure = -16,
                      .color_by = FC_COLOR_BY_SPEED, .colormap = FC_COLORMAP_COOLWARM,
                      .color_range = {-1e30f, 2.5f}, .jpeg_subsampling = FC_JPEG_SUBSAMPLING_YUV420,
                      .surface = FC_SURFACE_MODE_MESH, .surface_cell = 4.0f,
                      .surface_kernel = FC_SURFACE_KERNEL_ANISOTROPIC, .surface_smoothing = 100,
                      .spray_neighbours = 64, .contact_shadow = 1.0f, .depth_dimming = 0.125f,
                      .aerated_foam = 0.25f};
    fc_settings out;
    fc_settings_default(&out);
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    CHECK_CODE(fc_wire_write_settings(&b, 4, &in, &err), FC_OK);
    size_t n;
    const uint8_t *p = single_payload(&b, FC_MSG_SETTINGS, 4, &n);
    CHECK(n == 4 + 33 * 4 + 38 * 4);
    CHECK_CODE(fc_wire_read_settings(p, n, &out, &err), FC_OK);
    CHECK(memcmp(&in, &out, sizeof in) == 0);
    fc_buf_free(&b);
}

static void test_settings_partial_update(void)
{
    /* One entry: key 6 (ior), one word, 1.5f. */
    const uint8_t payload[] = {0x01, 0x00, 0x00, 0x00, 0x06, 0x00, 0x01, 0x00, 0x00, 0x00, 0xC0, 0x3F};
    fc_settings s, expected;
    fc_settings_default(&s);
    fc_settings_default(&expected);
    expected.ior = 1.5f;
    fc_error err;
    CHECK_CODE(fc_wire_read_settings(payload, sizeof payload, &s, &err), FC_OK);
    CHECK(memcmp(&s, &expected, sizeof s) == 0);

    /* No entries at all is a valid (empty) update. */
    const uint8_t empty[] = {0, 0, 0, 0};
    CHECK_CODE(fc_wire_read_settings(empty, sizeof empty, &s, &err), FC_OK);
    CHECK(memcmp(&s, &expected, sizeof s) == 0);
}

static void test_render_roundtrip(void)
{
    const fc_render_request requests[] = {
        {FC_FORMAT_PNG, 0, FC_AOV_COLOR},           {FC_FORMAT_JPEG, 1, FC_AOV_COLOR},
        {FC_FORMAT_JPEG, 100, FC_AOV_COLOR},        {FC_FORMAT_EXR, 0, FC_AOV_DEPTH},
        {FC_FORMAT_RAW, 0, FC_AOV_SMOOTHED_DEPTH}, {FC_FORMAT_EXR, 50, FC_AOV_THICKNESS},
    };
    for (size_t i = 0; i < sizeof requests / sizeof requests[0]; i++) {
        fc_render_request out;
        fc_buf b;
        fc_buf_init(&b);
        fc_error err;
        CHECK_CODE(fc_wire_write_render(&b, 5, &requests[i], &err), FC_OK);
        size_t n;
        const uint8_t *p = single_payload(&b, FC_MSG_RENDER, 5, &n);
        CHECK(n == 12);
        CHECK_CODE(fc_wire_read_render(p, n, &out, &err), FC_OK);
        CHECK(out.format == requests[i].format && out.aov == requests[i].aov);
        /* Quality 0 means the server default. */
        CHECK(out.quality == (requests[i].quality ? requests[i].quality : FC_DEFAULT_QUALITY));
        fc_buf_free(&b);
    }
    CHECK(FC_DEFAULT_QUALITY == 90);
}

static void test_image_roundtrip(void)
{
    const uint8_t pixels[7] = {0x89, 'P', 'N', 'G', 0, 1, 2};
    fc_image_reply in = {.width = 64, .height = 32, .format = FC_FORMAT_PNG, .aov = FC_AOV_COLOR,
                         .data = pixels, .size = sizeof pixels};
    for (int s = 0; s < FC_STAGE_COUNT; s++)
        in.stage_ms[s] = s == FC_STAGE_SMOOTHING ? -1.0f : 0.5f * s;
    fc_image_reply out;
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    CHECK_CODE(fc_wire_write_image(&b, 6, &in, &err), FC_OK);
    size_t n;
    const uint8_t *p = single_payload(&b, FC_MSG_IMAGE, 6, &n);
    /* Unmeasured stages are left out. */
    CHECK(n == 20 + (FC_STAGE_COUNT - 1) * 8 + 8 + sizeof pixels);
    CHECK_CODE(fc_wire_read_image(p, n, &out, &err), FC_OK);
    CHECK(out.width == 64 && out.height == 32 && out.format == FC_FORMAT_PNG && out.aov == FC_AOV_COLOR);
    for (int s = 0; s < FC_STAGE_COUNT; s++)
        CHECK_MSG(out.stage_ms[s] == in.stage_ms[s], "stage %d: %g != %g", s, out.stage_ms[s], in.stage_ms[s]);
    CHECK(out.size == sizeof pixels && memcmp(out.data, pixels, sizeof pixels) == 0);
    /* The data is not copied: it points into the payload. */
    CHECK(out.data >= p && out.data + out.size == p + n);
    fc_buf_free(&b);
}

static void test_image_skips_unknown_stages(void)
{
    const uint8_t payload[] = {
        0x02, 0, 0, 0, 0x01, 0, 0, 0,                           /* 2 x 1 */
        0x04, 0, 0, 0, 0x01, 0, 0, 0,                           /* RAW, depth */
        0x02, 0, 0, 0,                                          /* 2 stages */
        0x63, 0, 0, 0, 0x00, 0x00, 0x80, 0x3F,                  /* stage 99: 1 ms (unknown) */
        0x01, 0, 0, 0, 0x00, 0x00, 0x20, 0x40,                  /* stage 1 (depth): 2.5 ms */
        0x08, 0, 0, 0, 0, 0, 0, 0,                              /* 8 data bytes */
        0, 0, 0x80, 0x3F, 0, 0, 0, 0x40,                        /* 1.0f 2.0f */
    };
    fc_image_reply out;
    fc_error err;
    CHECK_CODE(fc_wire_read_image(payload, sizeof payload, &out, &err), FC_OK);
    CHECK(out.width == 2 && out.height == 1 && out.format == FC_FORMAT_RAW && out.aov == FC_AOV_DEPTH);
    for (int s = 0; s < FC_STAGE_COUNT; s++)
        CHECK_MSG(out.stage_ms[s] == (s == FC_STAGE_DEPTH ? 2.5f : -1.0f), "stage %d = %g", s, out.stage_ms[s]);
    CHECK(out.size == 8 && out.data == payload + sizeof payload - 8);
}

static void test_error_roundtrip(void)
{
    fc_error in, out, err;
    fc_error_set(&in, FC_ERR_INVALID_VALUE, "particle 12 has a non-finite position");
    fc_buf b;
    fc_buf_init(&b);
    CHECK_CODE(fc_wire_write_error(&b, 9, &in, &err), FC_OK);
    size_t n;
    const uint8_t *p = single_payload(&b, FC_MSG_ERROR, 9, &n);
    CHECK(n == 4 + 2 + strlen(in.message));
    CHECK_CODE(fc_wire_read_error(p, n, &out, &err), FC_OK);
    CHECK_CODE(out.code, FC_ERR_INVALID_VALUE);
    CHECK(strcmp(out.message, in.message) == 0);
    fc_buf_free(&b);
}

static void test_goodbye_roundtrip(void)
{
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    CHECK_CODE(fc_wire_write_goodbye(&b, 0, &err), FC_OK);
    size_t n;
    const uint8_t *p = single_payload(&b, FC_MSG_GOODBYE, 0, &n);
    CHECK(n == 0);
    CHECK_CODE(fc_wire_read_goodbye(p, n, &err), FC_OK);
    fc_buf_free(&b);
}

static void test_messages_append(void)
{
    /* Encoders append: several messages can be queued in one buffer. */
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    CHECK_CODE(fc_wire_write_goodbye(&b, 1, &err), FC_OK);
    CHECK_CODE(fc_wire_write_goodbye(&b, 2, &err), FC_OK);
    CHECK(b.len == 2 * FC_WIRE_HEADER_SIZE);
    fc_msg_header h;
    CHECK_CODE(fc_wire_decode_header(b.data + FC_WIRE_HEADER_SIZE, 0, &h, &err), FC_OK);
    CHECK(h.type == FC_MSG_GOODBYE && h.request_id == 2 && h.length == 0);
    fc_buf_reset(&b);
    CHECK(b.len == 0 && b.cap > 0);
    fc_buf_free(&b);
    CHECK(b.data == NULL && b.len == 0 && b.cap == 0);
}

static void test_hello_ignores_appended_fields(void)
{
    /* A later version may append fields to HELLO; v1 must still read its own. */
    const uint8_t payload[] = {1, 0, 0, 0, 2, 0, 0, 0, 0, 0, 0, 0, 1, 0, 'x', 0xAA, 0xBB, 0xCC};
    fc_hello out;
    fc_error err;
    CHECK_CODE(fc_wire_read_hello(payload, sizeof payload, &out, &err), FC_OK);
    CHECK(out.version_min == 1 && out.version_max == 2 && strcmp(out.client_name, "x") == 0);
}

static void test_long_string_is_cut_at_character_boundary(void)
{
    /* client_name holds 63 bytes: 62 'a' then a 2-byte 'é' would need 64, so the 'é' is dropped whole. */
    uint8_t payload[12 + 2 + 70];
    memset(payload, 0, 12);
    payload[0] = 1;
    payload[4] = 1;
    payload[12] = 70;
    payload[13] = 0;
    memset(payload + 14, 'a', 62);
    payload[14 + 62] = 0xC3;
    payload[14 + 63] = 0xA9;
    memset(payload + 14 + 64, 'b', 6);
    fc_hello out;
    fc_error err;
    CHECK_CODE(fc_wire_read_hello(payload, sizeof payload, &out, &err), FC_OK);
    CHECK(strlen(out.client_name) == 62);
    CHECK(out.client_name[61] == 'a');

    /* An ASCII name is cut at exactly 63 bytes. */
    memset(payload + 14, 'c', 70);
    CHECK_CODE(fc_wire_read_hello(payload, sizeof payload, &out, &err), FC_OK);
    CHECK(strlen(out.client_name) == 63);
}

static void test_failed_buffer_reports_nomem(void)
{
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    CHECK_CODE(fc_wire_write_goodbye(&b, 1, &err), FC_OK);
    CHECK(!fc_buf_reserve(&b, SIZE_MAX));
    CHECK(b.failed);
    CHECK_CODE(fc_wire_write_goodbye(&b, 2, &err), FC_ERR_NOMEM);
    CHECK_CODE(err.code, FC_ERR_NOMEM);
    /* The message that failed is not left half-written; the earlier one stays. */
    CHECK(b.len == FC_WIRE_HEADER_SIZE);
    fc_buf_reset(&b);
    CHECK(!b.failed);
    CHECK_CODE(fc_wire_write_goodbye(&b, 3, &err), FC_OK);
    fc_buf_free(&b);
}

static void test_writers_refuse_bad_arguments(void)
{
    fc_buf b;
    fc_buf_init(&b);
    fc_error err, local;
    fc_error_set(&local, FC_ERR_IO, "socket closed");
    CHECK_CODE(fc_wire_write_error(&b, 1, &local, &err), FC_ERR_USAGE);
    fc_frame empty = {0};
    CHECK_CODE(fc_wire_write_frame(&b, 1, &empty, &err), FC_ERR_USAGE);
    /* 2^32 particles cannot fit the 32-bit payload length; refused before any array is read. */
    float one[3] = {0, 0, 0};
    fc_frame huge = {.count = 1ull << 32, .positions = one};
    CHECK_CODE(fc_wire_write_frame(&b, 1, &huge, &err), FC_ERR_TOO_LARGE);
    fc_image_reply image = {.width = 1, .height = 1, .format = FC_FORMAT_RAW, .data = (const uint8_t *)one,
                            .size = UINT32_MAX};
    for (int s = 0; s < FC_STAGE_COUNT; s++)
        image.stage_ms[s] = -1;
    CHECK_CODE(fc_wire_write_image(&b, 1, &image, &err), FC_ERR_TOO_LARGE);
    CHECK(b.len == 0);
    fc_buf_free(&b);
}

int main(void)
{
    test_header_bytes();
    test_frame_bytes();
    test_frame_radius_bytes();
    test_frame_parts();
    test_hello_bytes();
    test_hello_roundtrip();
    test_welcome_roundtrip();
    test_welcome_device();
    test_frame_roundtrip_all_attributes();
    test_frame_roundtrip_each_attribute_set();
    test_camera_roundtrip();
    test_settings_roundtrip();
    test_settings_partial_update();
    test_render_roundtrip();
    test_image_roundtrip();
    test_image_skips_unknown_stages();
    test_error_roundtrip();
    test_goodbye_roundtrip();
    test_messages_append();
    test_hello_ignores_appended_fields();
    test_long_string_is_cut_at_character_boundary();
    test_failed_buffer_reports_nomem();
    test_writers_refuse_bad_arguments();
    return test_result();
}
