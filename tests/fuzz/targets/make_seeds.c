/* make_seeds.c — writes the generated part of the seed corpus: binary particle
 * files and one valid encoded message of every type (plus whole sessions, and
 * packed frames in every encoding), built with the fc_wire_write_* encoders. The text seeds (ascii PLY and VTK,
 * CSV) are written by hand and committed as they are.
 *
 * Usage: fuzz_make_seeds CORPUS_DIR   (CORPUS_DIR/<target>/ must exist) */
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <zlib.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "wire.h"
#include "wire_mesh.h"
#include "wire_scene.h"
#include "wire_session.h"
#include "wire_surface.h"

enum { SEED_PARTICLES = 4 };

static const float POSITIONS[SEED_PARTICLES][3] = {
    {0.0f, 0.0f, 0.0f}, {0.5f, 0.0f, 0.25f}, {0.0f, -1.5f, 2.0f}, {1e-3f, 300.0f, -7.0f}};
static const float DENSITY[SEED_PARTICLES] = {1000.0f, 998.5f, 1002.25f, 999.0f};
static const float VELOCITY[SEED_PARTICLES][3] = {
    {0.0f, 0.0f, -9.81f}, {1.0f, 2.0f, 3.0f}, {-0.5f, 0.25f, 0.0f}, {0.0f, 0.0f, 0.0f}};
static const uint32_t IDS[SEED_PARTICLES] = {0, 1, 7, 4294967295u};
/* Per-particle radii (FRAME attribute bit 3): the smallest and largest accepted, and two in between. */
static const float RADIUS[SEED_PARTICLES] = {0.05f, 0.1f, 0x1p-149f, 1e6f};

/* A complete 1x1 RGB PNG: what BACKGROUND and ENVIRONMENT carry (the codec frames the files, never decodes them). */
static const uint8_t PNG_1X1[] = {
    0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44, 0x52, 0x00, 0x00,
    0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x02, 0x00, 0x00, 0x00, 0x90, 0x77, 0x53, 0xde, 0x00, 0x00, 0x00,
    0x0c, 0x49, 0x44, 0x41, 0x54, 0x78, 0x9c, 0x63, 0x50, 0x48, 0x58, 0x00, 0x00, 0x01, 0xc4, 0x01, 0x21, 0x62,
    0x5f, 0x8a, 0xfd, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};

static const char SESSION_NAME[] = "sim/run-1";

/* ---- writing files ---- */

/* A failed reservation marks b failed, which save() reports. */
static void append(fc_buf *b, const void *bytes, size_t n)
{
    if (!fc_buf_reserve(b, n))
        return;
    memcpy(b->data + b->len, bytes, n);
    b->len += n;
}

static void append_text(fc_buf *b, const char *text)
{
    append(b, text, strlen(text));
}

/* A 4-byte word in the given byte order: floats go through their bit pattern. */
static void append_word(fc_buf *b, uint32_t word, bool big_endian)
{
    uint8_t bytes[4];
    for (int i = 0; i < 4; i++)
        bytes[i] = (uint8_t)(word >> (8 * (big_endian ? 3 - i : i)));
    append(b, bytes, sizeof bytes);
}

static void append_f32(fc_buf *b, float value, bool big_endian)
{
    uint32_t word;
    memcpy(&word, &value, sizeof word);
    append_word(b, word, big_endian);
}

static int save(const char *dir, const char *target, const char *file, const fc_buf *b)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s/%s", dir, target, file);
    FILE *out = fopen(path, "wb");
    if (out == NULL || b->failed || fwrite(b->data, 1, b->len, out) != b->len) {
        fprintf(stderr, "fuzz_make_seeds: cannot write %s\n", path);
        if (out)
            fclose(out);
        return 1;
    }
    return fclose(out) == 0 ? 0 : 1;
}

/* ---- particle files ---- */

static int write_f32(const char *dir)
{
    fc_buf b;
    fc_buf_init(&b);
    for (int i = 0; i < SEED_PARTICLES; i++)
        for (int k = 0; k < 3; k++)
            append_f32(&b, POSITIONS[i][k], false);
    int failed = save(dir, "fuzz_reader_f32", "particles.f32", &b);
    fc_buf_free(&b);
    return failed;
}

/* A PLY with an element before the vertices, a list property and an unused property. */
static int write_binary_ply(const char *dir, bool big_endian)
{
    fc_buf b;
    fc_buf_init(&b);
    append_text(&b, big_endian ? "ply\nformat binary_big_endian 1.0\n" : "ply\nformat binary_little_endian 1.0\n");
    append_text(&b, "element camera 1\nproperty float fov\nproperty list uchar int tags\n"
                    "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                    "property float density\nproperty float vx\nproperty float vy\nproperty float vz\n"
                    "property uint id\nproperty uchar red\nend_header\n");
    append_f32(&b, 45.0f, big_endian);
    append(&b, &(uint8_t){2}, 1);
    append_word(&b, 7, big_endian);
    append_word(&b, 8, big_endian);
    for (int i = 0; i < SEED_PARTICLES; i++) {
        for (int k = 0; k < 3; k++)
            append_f32(&b, POSITIONS[i][k], big_endian);
        append_f32(&b, DENSITY[i], big_endian);
        for (int k = 0; k < 3; k++)
            append_f32(&b, VELOCITY[i][k], big_endian);
        append_word(&b, IDS[i], big_endian);
        append(&b, &(uint8_t){200}, 1);
    }
    int failed = save(dir, "fuzz_reader_ply", big_endian ? "binary_be.ply" : "binary_le.ply", &b);
    fc_buf_free(&b);
    return failed;
}

/* VTK BINARY is big-endian; every block ends with a newline, as VTK's writer does. */
static void append_vtk_floats(fc_buf *b, const float *values, size_t count)
{
    for (size_t i = 0; i < count; i++)
        append_f32(b, values[i], true);
    append_text(b, "\n");
}

static void append_vtk_point_data(fc_buf *b)
{
    append_text(b, "POINT_DATA 4\nSCALARS density float 1\nLOOKUP_TABLE default\n");
    append_vtk_floats(b, DENSITY, SEED_PARTICLES);
    append_text(b, "VECTORS velocity float\n");
    append_vtk_floats(b, &VELOCITY[0][0], 3 * SEED_PARTICLES);
    append_text(b, "FIELD extra 1\nid 1 4 unsigned_int\n");
    for (int i = 0; i < SEED_PARTICLES; i++)
        append_word(b, IDS[i], true);
    append_text(b, "\n");
}

static int write_binary_vtk(const char *dir, bool unstructured)
{
    fc_buf b;
    fc_buf_init(&b);
    append_text(&b, "# vtk DataFile Version 3.0\nfuzz seed\nBINARY\n");
    append_text(&b, unstructured ? "DATASET UNSTRUCTURED_GRID\n" : "DATASET POLYDATA\n");
    append_text(&b, "POINTS 4 float\n");
    append_vtk_floats(&b, &POSITIONS[0][0], 3 * SEED_PARTICLES);
    append_text(&b, unstructured ? "CELLS 4 8\n" : "VERTICES 4 8\n");
    for (uint32_t i = 0; i < SEED_PARTICLES; i++) {
        append_word(&b, 1, true);
        append_word(&b, i, true);
    }
    append_text(&b, "\n");
    if (unstructured) {
        append_text(&b, "CELL_TYPES 4\n");
        for (int i = 0; i < SEED_PARTICLES; i++)
            append_word(&b, 1, true); /* VTK_VERTEX */
        append_text(&b, "\n");
    }
    append_vtk_point_data(&b);
    int failed = save(dir, "fuzz_reader_vtk", unstructured ? "binary_unstructured.vtk" : "binary_polydata.vtk", &b);
    fc_buf_free(&b);
    return failed;
}

/* A BGEO attribute definition with zero defaults, as partio writes it. */
static void append_bgeo_attribute(fc_buf *b, const char *name, uint16_t components, uint32_t type)
{
    uint8_t len[2] = {0, (uint8_t)strlen(name)};
    uint8_t size[2] = {(uint8_t)(components >> 8), (uint8_t)components};
    append(b, len, 2);
    append_text(b, name);
    append(b, size, 2);
    append_word(b, type, true);
    for (uint16_t k = 0; k < components; k++)
        append_word(b, 0, true);
}

/* Houdini classic BGEO V5 as partio writes it: header, v (vector), density (float), id (int), the points, 00 ff. */
static void build_bgeo(fc_buf *b)
{
    const uint32_t header[] = {5, SEED_PARTICLES, 0, 0, 0, 3, 0, 0, 0};
    append_text(b, "BgeoV");
    for (size_t i = 0; i < sizeof header / sizeof header[0]; i++)
        append_word(b, header[i], true);
    append_bgeo_attribute(b, "v", 3, 5);
    append_bgeo_attribute(b, "density", 1, 0);
    append_bgeo_attribute(b, "id", 1, 1);
    for (int i = 0; i < SEED_PARTICLES; i++) {
        for (int k = 0; k < 3; k++)
            append_f32(b, POSITIONS[i][k], true);
        append_f32(b, 1.0f, true);
        for (int k = 0; k < 3; k++)
            append_f32(b, VELOCITY[i][k], true);
        append_f32(b, DENSITY[i], true);
        append_word(b, IDS[i] & 0x7fffffffu, true);
    }
    append(b, "\x00\xff", 2);
}

/* The plain file, and the same gzip'd as partio does while keeping the .bgeo name. */
static int write_bgeo(const char *dir)
{
    fc_buf plain, packed;
    fc_buf_init(&plain);
    fc_buf_init(&packed);
    build_bgeo(&plain);
    int failed = save(dir, "fuzz_reader_bgeo", "classic.bgeo", &plain);
    z_stream z = {0};
    uint8_t out[4096];
    failed |= deflateInit2(&z, 6, Z_DEFLATED, 16 + MAX_WBITS, 8, Z_DEFAULT_STRATEGY) != Z_OK;
    z.next_in = plain.data;
    z.avail_in = (uInt)plain.len;
    z.next_out = out;
    z.avail_out = sizeof out;
    failed |= deflate(&z, Z_FINISH) != Z_STREAM_END;
    append(&packed, out, sizeof out - z.avail_out);
    deflateEnd(&z);
    failed |= save(dir, "fuzz_reader_bgeo", "gzip.bgeo", &packed);
    fc_buf_free(&plain);
    fc_buf_free(&packed);
    return failed;
}

/* numpy .npy version 1.0, the header padded as numpy pads it (to 64 bytes with a newline), then the positions. */
static int write_npy(const char *dir, bool fortran)
{
    char header[128];
    int len = snprintf(header, sizeof header, "{'descr': '<f4', 'fortran_order': %s, 'shape': (%d, 3), }",
                       fortran ? "True" : "False", SEED_PARTICLES);
    fc_buf b;
    fc_buf_init(&b);
    append(&b, "\x93NUMPY\x01\x00\x76\x00", 10); /* header length 118: 10 + 118 = 128 */
    append(&b, header, (size_t)len);
    for (int i = len; i < 117; i++)
        append_text(&b, " ");
    append_text(&b, "\n");
    for (int at = 0; at < 3 * SEED_PARTICLES; at++)
        append_f32(&b, fortran ? POSITIONS[at % SEED_PARTICLES][at / SEED_PARTICLES] : POSITIONS[at / 3][at % 3], false);
    int failed = save(dir, "fuzz_reader_npy", fortran ? "fortran.npy" : "c_order.npy", &b);
    fc_buf_free(&b);
    return failed;
}

/* ---- messages ---- */

typedef fc_code (*message_writer)(fc_buf *out);

static fc_code write_hello(fc_buf *out)
{
    fc_hello m = {.version_min = 1, .version_max = 1, .capabilities = 0, .client_name = "fuzz seed"};
    return fc_wire_write_hello(out, 1, &m, NULL);
}

static fc_code write_welcome(fc_buf *out)
{
    fc_welcome m = {.version = 1,
                    .limits = {.max_particles = 1000000, .max_width = 4096, .max_height = 4096, .max_message = 1 << 26},
                    .server_version = "fluidcastd 0.1.0",
                    .renderer = "llvmpipe"};
    return fc_wire_write_welcome(out, 1, &m, NULL);
}

/* WELCOME with capability DEVICE: the optional `device` field after `renderer`. */
static fc_code write_welcome_device(fc_buf *out)
{
    fc_welcome m = {.version = 1,
                    .capabilities = FC_CAP_DEVICE,
                    .limits = {.max_particles = 1000000, .max_width = 4096, .max_height = 4096, .max_message = 1 << 26},
                    .server_version = "fluidcastd 0.1.0",
                    .renderer = "llvmpipe",
                    .device = "EGL device 0, /dev/dri/renderD128, CUDA 0"};
    return fc_wire_write_welcome(out, 1, &m, NULL);
}

/* Particles first .. first + count - 1 of the seed particles. */
static fc_frame seed_part(size_t first, size_t count, bool with_attributes)
{
    fc_frame frame = {.count = count, .positions = (float *)&POSITIONS[first][0]};
    if (with_attributes) {
        frame.density = (float *)&DENSITY[first];
        frame.velocity = (float *)&VELOCITY[first][0];
        frame.ids = (uint32_t *)&IDS[first];
    }
    return frame;
}

static fc_frame seed_frame(bool with_attributes)
{
    return seed_part(0, SEED_PARTICLES, with_attributes);
}

static fc_code write_frame_positions(fc_buf *out)
{
    fc_frame frame = seed_frame(false);
    return fc_wire_write_frame(out, 2, &frame, NULL);
}

static fc_code write_frame_all(fc_buf *out)
{
    fc_frame frame = seed_frame(true);
    return fc_wire_write_frame(out, 2, &frame, NULL);
}

/* Positions and per-particle radii only, then every attribute. */
static fc_code write_frame_radius(fc_buf *out)
{
    fc_frame frame = seed_frame(false);
    frame.radius = (float *)RADIUS;
    return fc_wire_write_frame(out, 2, &frame, NULL);
}

static fc_code write_frame_all_radius(fc_buf *out)
{
    fc_frame frame = seed_frame(true);
    frame.radius = (float *)RADIUS;
    return fc_wire_write_frame(out, 2, &frame, NULL);
}

static fc_code write_camera(fc_buf *out)
{
    fc_camera m = {.eye = {3, -4, 2}, .target = {0, 0, 0}, .up = {0, 0, 1}, .fov_y_deg = 40, .width = 64, .height = 48};
    return fc_wire_write_camera(out, 3, &m, NULL);
}

static fc_code write_settings(fc_buf *out)
{
    fc_settings m;
    fc_settings_default(&m);
    m.radius = 0.05f;
    return fc_wire_write_settings(out, 4, &m, NULL);
}

static fc_code write_render(fc_buf *out)
{
    fc_render_request m = {.format = FC_FORMAT_EXR, .quality = 0, .aov = FC_AOV_DEPTH};
    return fc_wire_write_render(out, 5, &m, NULL);
}

static fc_image_reply seed_image(void)
{
    static const uint8_t pixels[2 * 2 * 4] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 9, 9, 9, 0};
    fc_image_reply m = {.width = 2, .height = 2, .format = FC_FORMAT_RAW, .aov = FC_AOV_COLOR,
                        .data = pixels, .size = sizeof pixels};
    for (int s = 0; s < FC_STAGE_COUNT; s++)
        m.stage_ms[s] = s == FC_STAGE_SMOOTHING ? -1.0f : 0.5f * (float)s; /* one stage not measured */
    return m;
}

static fc_code write_image(fc_buf *out)
{
    fc_image_reply m = seed_image();
    return fc_wire_write_image(out, 5, &m, NULL);
}

static fc_code write_error(fc_buf *out)
{
    fc_error m = {FC_ERR_BAD_STATE, "RENDER before FRAME"};
    return fc_wire_write_error(out, 5, &m, NULL);
}

static fc_code write_goodbye(fc_buf *out)
{
    return fc_wire_write_goodbye(out, 6, NULL);
}

static fc_code write_background(fc_buf *out)
{
    fc_encoded_image image = {PNG_1X1, sizeof PNG_1X1};
    return fc_wire_write_background(out, 7, &image, NULL);
}

static fc_code write_environment(fc_buf *out)
{
    fc_encoded_image faces[FC_CUBE_FACES];
    for (int i = 0; i < FC_CUBE_FACES; i++)
        faces[i] = (fc_encoded_image){PNG_1X1, sizeof PNG_1X1};
    return fc_wire_write_environment(out, 8, faces, NULL);
}

/* The empty payloads that return to the built-in floor, sky and reflections. */
static fc_code write_background_reset(fc_buf *out)
{
    return fc_wire_write_background(out, 9, NULL, NULL);
}

static fc_code write_environment_reset(fc_buf *out)
{
    return fc_wire_write_environment(out, 10, NULL, NULL);
}

/* ---- session messages ---- */

static fc_session_info seed_session_info(const char *name, uint32_t producers, uint64_t frames)
{
    fc_session_info m = {.producers = producers, .viewers = 1, .frames = frames, .last_frame = 40 + frames};
    snprintf(m.name, sizeof m.name, "%s", name);
    return m;
}

static fc_code write_publish(fc_buf *out)
{
    return fc_wire_write_publish(out, 1, SESSION_NAME, NULL);
}

static fc_code write_subscribe(fc_buf *out)
{
    fc_subscribe m = {.request = {.format = FC_FORMAT_JPEG, .quality = 80, .aov = FC_AOV_COLOR},
                      .width = 64, .height = 48};
    snprintf(m.name, sizeof m.name, "%s", SESSION_NAME);
    return fc_wire_write_subscribe(out, 2, &m, NULL);
}

static fc_code write_subscribe_h264(fc_buf *out)
{
    fc_subscribe m = {.request = {.format = FC_FORMAT_H264, .quality = 0, .aov = FC_AOV_COLOR},
                      .width = 64, .height = 48};
    snprintf(m.name, sizeof m.name, "%s", SESSION_NAME);
    return fc_wire_write_subscribe(out, 2, &m, NULL);
}

static fc_code write_session_state(fc_buf *out)
{
    fc_session_info m = seed_session_info(SESSION_NAME, 2, 3);
    return fc_wire_write_session_state(out, 2, &m, NULL);
}

static fc_code write_session_leave(fc_buf *out)
{
    return fc_wire_write_session_leave(out, 9, NULL);
}

static fc_code write_session_end(fc_buf *out)
{
    return fc_wire_write_session_end(out, 2, SESSION_NAME, NULL);
}

static fc_code write_list_sessions(fc_buf *out)
{
    return fc_wire_write_list_sessions(out, 3, NULL);
}

static fc_code write_session_list(fc_buf *out)
{
    fc_session_info m[2] = {seed_session_info(SESSION_NAME, 2, 3), seed_session_info("rank-test", 0, 0)};
    return fc_wire_write_session_list(out, 3, m, 2, NULL);
}

static fc_code write_stream_image(fc_buf *out)
{
    fc_stream_tag tag = {.frame_number = 41, .sequence = 3, .missed = 1, .flags = 0};
    fc_image_reply image = seed_image();
    return fc_wire_write_stream_image(out, 2, &tag, &image, NULL);
}

/* An H.264 key frame's shape: SPS, PPS and IDR slice NAL units behind Annex B start codes. */
static fc_code write_stream_image_h264(fc_buf *out)
{
    static const uint8_t unit[] = {0, 0, 0, 1, 0x67, 0x64, 0x00, 0x0a, 0, 0, 0, 1, 0x68, 0xee, 0x3c,
                                   0, 0, 1, 0x65, 0x88, 0x84, 0x00};
    fc_stream_tag tag = {.frame_number = 42, .sequence = 4, .missed = 0, .flags = FC_STREAM_KEYFRAME};
    fc_image_reply image = seed_image();
    image.format = FC_FORMAT_H264;
    image.data = unit;
    image.size = sizeof unit;
    return fc_wire_write_stream_image(out, 2, &tag, &image, NULL);
}

/* Frame 41 in two chunks of 1 and 3 particles: odd counts, so quantised ones carry padding. */
static fc_code write_chunk_plain(fc_buf *out)
{
    fc_chunk_header h = {.frame_number = 41, .index = 0, .count = 2};
    fc_frame part = seed_part(0, 1, true);
    return fc_wire_write_chunk(out, 4, &h, &part, 0, 0, NULL);
}

static fc_code write_chunk_packed(fc_buf *out)
{
    fc_chunk_header h = {.frame_number = 41, .index = 1, .count = 2};
    fc_frame part = seed_part(1, SEED_PARTICLES - 1, true);
    return fc_wire_write_chunk(out, 5, &h, &part, FC_PACK_ZSTD | FC_PACK_QUANTIZE16, 0, NULL);
}

static fc_code write_frame_packed(fc_buf *out, uint32_t encoding)
{
    fc_frame frame = seed_frame(true);
    return fc_wire_write_frame_packed(out, 6, &frame, encoding, 0, NULL);
}

static fc_code write_frame_packed_plain(fc_buf *out)
{
    return write_frame_packed(out, 0);
}

static fc_code write_frame_packed_zstd(fc_buf *out)
{
    return write_frame_packed(out, FC_PACK_ZSTD);
}

static fc_code write_frame_packed_quantized(fc_buf *out)
{
    return write_frame_packed(out, FC_PACK_QUANTIZE16);
}

/* Radii after the ids in the quantised layout, and in a zstd'd plain one. */
static fc_code write_frame_packed_radius(fc_buf *out, uint32_t encoding)
{
    fc_frame frame = seed_frame(true);
    frame.radius = (float *)RADIUS;
    return fc_wire_write_frame_packed(out, 6, &frame, encoding, 0, NULL);
}

static fc_code write_frame_packed_radius_quantized(fc_buf *out)
{
    return write_frame_packed_radius(out, FC_PACK_QUANTIZE16);
}

static fc_code write_frame_packed_radius_zstd(fc_buf *out)
{
    return write_frame_packed_radius(out, FC_PACK_ZSTD);
}

static fc_code write_frame_packed_positions(fc_buf *out)
{
    fc_frame frame = seed_frame(false);
    return fc_wire_write_frame_packed(out, 6, &frame, FC_PACK_ZSTD | FC_PACK_QUANTIZE16, 0, NULL);
}

/* ---- saving messages ---- */

typedef struct seed_file {
    const char *file;
    message_writer writer;
} seed_file;

static int save_messages(const char *dir, const char *target, const char *file, const message_writer *writers,
                         size_t count)
{
    fc_buf b;
    fc_buf_init(&b);
    int failed = 0;
    for (size_t i = 0; i < count; i++)
        failed |= writers[i](&b) != FC_OK;
    failed |= save(dir, target, file, &b);
    fc_buf_free(&b);
    return failed;
}

static int save_singles(const char *dir, const char *target, const seed_file *files, size_t count)
{
    int failed = 0;
    for (size_t i = 0; i < count; i++)
        failed |= save_messages(dir, target, files[i].file, &files[i].writer, 1);
    return failed;
}

#define COUNT(array) (sizeof(array) / sizeof((array)[0]))

static int write_messages(const char *dir)
{
    static const seed_file singles[] = {
        {"hello.bin", write_hello},     {"welcome.bin", write_welcome},
        {"welcome_device.bin", write_welcome_device},
        {"frame.bin", write_frame_positions}, {"frame_attributes.bin", write_frame_all},
        {"frame_radius.bin", write_frame_radius}, {"frame_attributes_radius.bin", write_frame_all_radius},
        {"camera.bin", write_camera},   {"settings.bin", write_settings},
        {"render.bin", write_render},   {"image.bin", write_image},
        {"error.bin", write_error},     {"goodbye.bin", write_goodbye},
        {"background.bin", write_background}, {"environment.bin", write_environment},
    };
    static const message_writer session[] = {write_hello,    write_frame_all, write_camera,
                                             write_settings, write_render,    write_goodbye};
    static const message_writer scene_reset[] = {write_background_reset, write_environment_reset};
    const char *target = "fuzz_wire_messages";
    return save_singles(dir, target, singles, COUNT(singles)) |
           save_messages(dir, target, "session.bin", session, COUNT(session)) |
           save_messages(dir, target, "scene_reset.bin", scene_reset, COUNT(scene_reset));
}

static int write_session_messages(const char *dir)
{
    static const seed_file singles[] = {
        {"publish.bin", write_publish},
        {"subscribe.bin", write_subscribe},
        {"session_state.bin", write_session_state},
        {"session_leave.bin", write_session_leave},
        {"session_end.bin", write_session_end},
        {"list_sessions.bin", write_list_sessions},
        {"session_list.bin", write_session_list},
        {"stream_image.bin", write_stream_image},
        {"subscribe_h264.bin", write_subscribe_h264},
        {"stream_image_h264.bin", write_stream_image_h264},
        {"chunk.bin", write_chunk_plain},
        {"chunk_zstd_quantized.bin", write_chunk_packed},
        {"frame_packed.bin", write_frame_packed_plain},
        {"frame_packed_zstd.bin", write_frame_packed_zstd},
        {"frame_packed_quantized.bin", write_frame_packed_quantized},
        {"frame_packed_radius_quantized.bin", write_frame_packed_radius_quantized},
        {"frame_packed_radius_zstd.bin", write_frame_packed_radius_zstd},
        {"frame_packed_positions_zstd_quantized.bin", write_frame_packed_positions},
    };
    static const message_writer producer[] = {write_publish, write_chunk_plain, write_chunk_packed,
                                              write_frame_packed_zstd, write_session_leave};
    static const message_writer viewer[] = {write_subscribe, write_session_state, write_stream_image,
                                            write_list_sessions, write_session_list, write_session_end};
    const char *target = "fuzz_wire_session";
    return save_singles(dir, target, singles, COUNT(singles)) |
           save_messages(dir, target, "producer.bin", producer, COUNT(producer)) |
           save_messages(dir, target, "viewer.bin", viewer, COUNT(viewer));
}

/* A 4-vertex quad (two triangles), with normals and hide-near when `normals`. */
static fc_code write_mesh_quad(fc_buf *out, bool normals)
{
    static const float vertices[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    static const float up[12] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
    static const uint32_t indices[6] = {0, 1, 2, 0, 2, 3};
    fc_mesh m = {.id = 3, .flags = normals ? FC_MESH_HIDE_NEAR : 0, .vertex_count = 4, .triangle_count = 2,
                 .vertices = vertices, .indices = indices, .normals = normals ? up : NULL,
                 .color = {0.2f, 0.4f, 0.6f}, .opacity = normals ? 0.3f : 1.0f};
    fc_mesh_identity(m.transform);
    return fc_wire_write_mesh(out, 12, &m, NULL);
}

static fc_code write_mesh_plain(fc_buf *out) { return write_mesh_quad(out, false); }
static fc_code write_mesh_normals(fc_buf *out) { return write_mesh_quad(out, true); }
static fc_code write_mesh_removal(fc_buf *out) { return fc_wire_write_mesh_removal(out, 13, 3, NULL); }

static fc_code write_mesh_transforms(fc_buf *out)
{
    fc_mesh_transform e[2] = {{.id = 3}, {.id = 4}};
    fc_mesh_identity(e[0].transform);
    fc_mesh_identity(e[1].transform);
    e[1].transform[11] = -2.5f;
    return fc_wire_write_mesh_transforms(out, 14, e, 2, NULL);
}

static int write_mesh_messages(const char *dir)
{
    static const seed_file singles[] = {
        {"mesh.bin", write_mesh_plain},
        {"mesh_normals.bin", write_mesh_normals},
        {"mesh_removal.bin", write_mesh_removal},
        {"mesh_transform.bin", write_mesh_transforms},
    };
    static const message_writer sequence[] = {write_mesh_plain, write_mesh_normals, write_mesh_transforms,
                                              write_mesh_removal};
    const char *target = "fuzz_wire_mesh";
    return save_singles(dir, target, singles, COUNT(singles)) |
           save_messages(dir, target, "sequence.bin", sequence, COUNT(sequence));
}

/* A tetrahedron with every attribute: four vertices, four triangles. */
static fc_code write_surface_tetrahedron(fc_buf *out)
{
    float positions[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    float normals[12] = {-0.57735f, -0.57735f, -0.57735f, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    uint32_t indices[12] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
    float speed[4] = {0, 1, 2, 3}, density[4] = {1000, 1001, 1002, 1003};
    float velocity[12] = {0, 0, 0, 1, 0, 0, 0, 2, 0, 0, 0, 3};
    uint32_t id[4] = {10, 11, 12, 13};
    fc_surface_mesh m = {.vertex_count = 4, .triangle_count = 4, .positions = positions, .normals = normals,
                         .indices = indices, .attributes = FC_SURFACE_ATTRIBUTES_ALL, .speed = speed,
                         .density = density, .velocity = velocity, .id = id};
    return fc_wire_write_surface_part(out, 15, &m, 2.5f, 0, NULL);
}

/* The same without attributes, as an OBJ or STL export asks. */
static fc_code write_surface_plain(fc_buf *out)
{
    float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0}, normals[9] = {0, 0, 1, 0, 0, 1, 0, 0, 1};
    uint32_t indices[3] = {0, 1, 2};
    fc_surface_mesh m = {.vertex_count = 3, .triangle_count = 1, .positions = positions, .normals = normals,
                         .indices = indices};
    return fc_wire_write_surface_part(out, 16, &m, -1.0f, 0, NULL);
}

static fc_code write_surface_empty(fc_buf *out)
{
    fc_surface_mesh none = {0};
    return fc_wire_write_surface_part(out, 17, &none, 0.0f, 0, NULL);
}

static fc_code write_surface_request(fc_buf *out)
{
    return fc_wire_write_surface_request(out, 15, FC_SURFACE_ATTRIBUTES_ALL, NULL);
}

static int write_surface_messages(const char *dir)
{
    static const seed_file singles[] = {
        {"request.bin", write_surface_request},
        {"tetrahedron.bin", write_surface_tetrahedron},
        {"plain.bin", write_surface_plain},
        {"empty.bin", write_surface_empty},
    };
    static const message_writer sequence[] = {write_surface_request, write_surface_tetrahedron, write_surface_plain,
                                              write_surface_empty};
    const char *target = "fuzz_wire_surface";
    return save_singles(dir, target, singles, COUNT(singles)) |
           save_messages(dir, target, "sequence.bin", sequence, COUNT(sequence));
}

/* fuzz_wire_settings takes bare payloads: the SETTINGS message without its header. */
static int write_settings_payloads(const char *dir)
{
    fc_buf message, payload;
    fc_buf_init(&message);
    fc_buf_init(&payload);
    int failed = write_settings(&message) != FC_OK;
    if (!failed)
        append(&payload, message.data + FC_WIRE_HEADER_SIZE, message.len - FC_WIRE_HEADER_SIZE);
    failed |= save(dir, "fuzz_wire_settings", "all.bin", &payload);

    /* Two entries in reverse key order: iterations = 3 (key 3), ior = 1.5 (key 6). */
    fc_buf_reset(&payload);
    append_word(&payload, 2, false);
    append_word(&payload, 6u | 1u << 16, false);
    append_f32(&payload, 1.5f, false);
    append_word(&payload, 3u | 1u << 16, false);
    append_word(&payload, 3, false);
    failed |= save(dir, "fuzz_wire_settings", "some.bin", &payload);

    /* Keys of the optional effects: smooth_scale = 0.5 (key 8), noise = 0.5 (key 14), foam = 1 (key 15). */
    fc_buf_reset(&payload);
    append_word(&payload, 3, false);
    append_word(&payload, 8u | 1u << 16, false);
    append_f32(&payload, 0.5f, false);
    append_word(&payload, 14u | 1u << 16, false);
    append_f32(&payload, 0.5f, false);
    append_word(&payload, 15u | 1u << 16, false);
    append_f32(&payload, 1.0f, false);
    failed |= save(dir, "fuzz_wire_settings", "effects.bin", &payload);
    fc_buf_free(&message);
    fc_buf_free(&payload);
    return failed;
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: %s CORPUS_DIR\n", argv[0]);
        return 2;
    }
    const char *dir = argv[1];
    int failed = write_f32(dir) | write_binary_ply(dir, false) | write_binary_ply(dir, true) |
                 write_binary_vtk(dir, false) | write_binary_vtk(dir, true) | write_bgeo(dir) | write_npy(dir, false) | write_npy(dir, true) | write_messages(dir) |
                 write_session_messages(dir) | write_settings_payloads(dir) | write_mesh_messages(dir) |
                 write_surface_messages(dir);
    return failed ? 1 : 0;
}
