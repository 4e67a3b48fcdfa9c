/* make_seeds.c — writes the generated part of the seed corpus: binary particle
 * files and one valid encoded message of every type (plus a whole session),
 * built with the fc_wire_write_* encoders. The text seeds (ascii PLY and VTK,
 * CSV) are written by hand and committed as they are.
 *
 * Usage: fuzz_make_seeds CORPUS_DIR   (CORPUS_DIR/<target>/ must exist) */
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "wire.h"

enum { SEED_PARTICLES = 4 };

static const float POSITIONS[SEED_PARTICLES][3] = {
    {0.0f, 0.0f, 0.0f}, {0.5f, 0.0f, 0.25f}, {0.0f, -1.5f, 2.0f}, {1e-3f, 300.0f, -7.0f}};
static const float DENSITY[SEED_PARTICLES] = {1000.0f, 998.5f, 1002.25f, 999.0f};
static const float VELOCITY[SEED_PARTICLES][3] = {
    {0.0f, 0.0f, -9.81f}, {1.0f, 2.0f, 3.0f}, {-0.5f, 0.25f, 0.0f}, {0.0f, 0.0f, 0.0f}};
static const uint32_t IDS[SEED_PARTICLES] = {0, 1, 7, 4294967295u};

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

static fc_frame seed_frame(bool with_attributes)
{
    fc_frame frame = {.count = SEED_PARTICLES, .positions = (float *)&POSITIONS[0][0]};
    if (with_attributes) {
        frame.density = (float *)DENSITY;
        frame.velocity = (float *)&VELOCITY[0][0];
        frame.ids = (uint32_t *)IDS;
    }
    return frame;
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

static fc_code write_image(fc_buf *out)
{
    static const uint8_t pixels[2 * 2 * 4] = {255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 9, 9, 9, 0};
    fc_image_reply m = {.width = 2, .height = 2, .format = FC_FORMAT_RAW, .aov = FC_AOV_COLOR,
                        .data = pixels, .size = sizeof pixels};
    for (int s = 0; s < FC_STAGE_COUNT; s++)
        m.stage_ms[s] = s == FC_STAGE_SMOOTHING ? -1.0f : 0.5f * (float)s; /* one stage not measured */
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

static int save_messages(const char *dir, const char *file, const message_writer *writers, size_t count)
{
    fc_buf b;
    fc_buf_init(&b);
    int failed = 0;
    for (size_t i = 0; i < count; i++)
        failed |= writers[i](&b) != FC_OK;
    failed |= save(dir, "fuzz_wire_messages", file, &b);
    fc_buf_free(&b);
    return failed;
}

static int write_messages(const char *dir)
{
    static const struct {
        const char *file;
        message_writer writer;
    } singles[] = {
        {"hello.bin", write_hello},     {"welcome.bin", write_welcome},
        {"frame.bin", write_frame_positions}, {"frame_attributes.bin", write_frame_all},
        {"camera.bin", write_camera},   {"settings.bin", write_settings},
        {"render.bin", write_render},   {"image.bin", write_image},
        {"error.bin", write_error},     {"goodbye.bin", write_goodbye},
    };
    static const message_writer session[] = {write_hello,    write_frame_all, write_camera,
                                             write_settings, write_render,    write_goodbye};
    int failed = 0;
    for (size_t i = 0; i < sizeof singles / sizeof singles[0]; i++)
        failed |= save_messages(dir, singles[i].file, &singles[i].writer, 1);
    failed |= save_messages(dir, "session.bin", session, sizeof session / sizeof session[0]);
    return failed;
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
                 write_binary_vtk(dir, false) | write_binary_vtk(dir, true) | write_messages(dir) |
                 write_settings_payloads(dir);
    return failed ? 1 : 0;
}
