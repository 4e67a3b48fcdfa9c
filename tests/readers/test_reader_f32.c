/* test_reader_f32.c — raw little-endian float32 xyz files, and the shared sample
 * data set against its JSON sidecar when ../shared/data is there. */
#include "reader_test_support.h"

/* 1.0f, -2.5f, 0.15625f and 1e30f as little-endian bytes, written out by hand. */
static const uint8_t ONE[4] = { 0x00, 0x00, 0x80, 0x3f };
static const uint8_t MINUS_2_5[4] = { 0x00, 0x00, 0x20, 0xc0 };
static const uint8_t F_0_15625[4] = { 0x00, 0x00, 0x20, 0x3e };
static const uint8_t NAN_BITS[4] = { 0x00, 0x00, 0xc0, 0x7f };
static const uint8_t INF_BITS[4] = { 0x00, 0x00, 0x80, 0x7f };

static bytes two_particles(void)
{
    bytes b = { NULL, 0, 0 };
    const uint8_t *values[6] = { ONE, MINUS_2_5, F_0_15625, F_0_15625, ONE, MINUS_2_5 };
    for (int i = 0; i < 6; i++)
        bytes_append(&b, values[i], 4);
    return b;
}

static void test_values_little_endian(void)
{
    bytes b = two_particles();
    fc_frame frame;
    fc_error err;
    CHECK_CODE(fc_read_particles_mem(b.data, b.len, FC_FILE_F32, "two.f32", &frame, &err), FC_OK);
    CHECK(frame.count == 2);
    check_position(&frame, 0, 1.0f, -2.5f, 0.15625f);
    check_position(&frame, 1, 0.15625f, 1.0f, -2.5f);
    CHECK(frame.density == NULL && frame.velocity == NULL && frame.ids == NULL);
    fc_frame_free(&frame);
    bytes_free(&b);
}

static void test_bad_sizes_and_values(void)
{
    bytes b = two_particles();
    b.len = 13;
    expect_failure(&b, FC_FILE_F32, "odd.f32", FC_ERR_PARSE, "13 bytes is not a multiple of 12");
    b.len = 0;
    expect_failure(&b, FC_FILE_F32, "empty.f32", FC_ERR_PARSE, "empty file");
    b.len = 24;
    memcpy(b.data + 16, NAN_BITS, 4);
    CHECK_MSG(strcmp(expect_failure(&b, FC_FILE_F32, "nan.f32", FC_ERR_PARSE, NULL),
                     "nan.f32: byte offset 16: particle 1: y = nan is not a finite value in float range") == 0,
              "exact message");
    memcpy(b.data + 16, ONE, 4);
    memcpy(b.data + 0, INF_BITS, 4);
    expect_failure(&b, FC_FILE_F32, "inf.f32", FC_ERR_PARSE, "byte offset 0: particle 0: x = inf");
    bytes_free(&b);
}

/* Read from a file, the buffer the file was read into becomes the positions
 * (reader_f32.c): the same values, the same errors, and the frame frees it
 * (ASan's leak check and double-free check run this too). */
static void test_from_a_file(void)
{
    bytes b = two_particles();
    fc_frame frame;
    fc_error err;
    CHECK_CODE(fc_read_particles(write_temp_file("two.f32", &b), &frame, &err), FC_OK);
    CHECK(frame.count == 2);
    check_position(&frame, 0, 1.0f, -2.5f, 0.15625f);
    check_position(&frame, 1, 0.15625f, 1.0f, -2.5f);
    fc_frame_free(&frame);
    memcpy(b.data + 16, NAN_BITS, 4);
    CHECK_CODE(fc_read_particles(write_temp_file("nan.f32", &b), &frame, &err), FC_ERR_PARSE);
    CHECK_MSG(strstr(err.message, "byte offset 16: particle 1: y = nan") != NULL, "%s", err.message);
    CHECK(frame_is_empty(&frame));
    b.len = 13;
    CHECK_CODE(fc_read_particles(write_temp_file("odd.f32", &b), &frame, &err), FC_ERR_PARSE);
    CHECK(frame_is_empty(&frame));
    bytes_free(&b);
}

static void test_truncations(void)
{
    bytes b = { NULL, 0, 0 };
    for (int i = 0; i < 5 * 3; i++)
        bytes_f32(&b, (float)i * 0.25f, false);
    /* Every length that is not a whole number of particles fails; whole ones give exactly len/12. */
    for (size_t len = 0; len < b.len; len++) {
        fc_frame frame;
        fc_error err;
        fc_code code = fc_read_particles_mem(b.data, len, FC_FILE_F32, "cut.f32", &frame, &err);
        if (len % 12 == 0 && len > 0) {
            CHECK_CODE(code, FC_OK);
            CHECK(frame.count == len / 12);
            CHECK(frame.positions[3 * frame.count - 1] == (float)(3 * frame.count - 1) * 0.25f);
        } else {
            CHECK_CODE(code, FC_ERR_PARSE);
            CHECK(frame_is_empty(&frame));
        }
        fc_frame_free(&frame);
    }
    bytes_free(&b);
}

/* Finds `"key": <number>` (or the key's array, element `index`) in a small JSON text. */
static bool json_number(const char *json, const char *key, int index, double *out)
{
    char quoted[64];
    snprintf(quoted, sizeof quoted, "\"%s\"", key);
    const char *p = strstr(json, quoted);
    if (p == NULL || (p = strchr(p + strlen(quoted), ':')) == NULL)
        return false;
    p++;
    if (index >= 0) {
        if ((p = strchr(p, '[')) == NULL)
            return false;
        p++;
        for (int i = 0; i < index; i++) {
            if ((p = strchr(p, ',')) == NULL)
                return false;
            p++;
        }
    }
    char *end = NULL;
    *out = strtod(p, &end);
    return end != p;
}

static char *slurp(const char *path)
{
    FILE *file = fopen(path, "rb");
    if (file == NULL)
        return NULL;
    char *text = calloc(1, 1 << 16);
    size_t n = fread(text, 1, (1 << 16) - 1, file);
    fclose(file);
    text[n] = '\0';
    return text;
}

static void test_shared_dambreak(const char *data_dir)
{
    char f32_path[1024], json_path[1024];
    snprintf(f32_path, sizeof f32_path, "%s/dambreak_16k.f32", data_dir);
    snprintf(json_path, sizeof json_path, "%s/dambreak_16k.json", data_dir);
    char *json = slurp(json_path);
    if (json == NULL || access(f32_path, R_OK) != 0) {
        printf("skipped: %s not present\n", f32_path);
        free(json);
        return;
    }
    double n = 0, lo[3] = { 0 }, hi[3] = { 0 };
    CHECK(json_number(json, "N", -1, &n));
    for (int a = 0; a < 3; a++) {
        CHECK(json_number(json, "bbox_min", a, &lo[a]));
        CHECK(json_number(json, "bbox_max", a, &hi[a]));
    }
    free(json);
    fc_frame frame;
    fc_error err;
    CHECK_CODE(fc_read_particles(f32_path, &frame, &err), FC_OK);
    CHECK_MSG(frame.count == (uint64_t)n, "count %llu, sidecar N %g", (unsigned long long)frame.count, n);
    for (int a = 0; a < 3 && frame.count > 0; a++) {
        float min = frame.positions[a], max = frame.positions[a];
        for (uint64_t i = 1; i < frame.count; i++) {
            float v = frame.positions[3 * i + (uint64_t)a];
            min = v < min ? v : min;
            max = v > max ? v : max;
        }
        CHECK_NEAR(min, lo[a], 1e-6);
        CHECK_NEAR(max, hi[a], 1e-6);
    }
    fc_frame_free(&frame);
}

int main(int argc, char **argv)
{
    test_values_little_endian();
    test_bad_sizes_and_values();
    test_truncations();
    test_from_a_file();
    test_shared_dambreak(argc > 1 ? argv[1] : "../shared/data");
    return test_result();
}
