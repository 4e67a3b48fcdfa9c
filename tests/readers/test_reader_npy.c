/* test_reader_npy.c — numpy .npy arrays: files written by numpy itself (when
 * make_npy_fixtures.py could run with Debian's python3-numpy: float32 and float64,
 * versions 1.0 and 2.0, Fortran order, big-endian, and the shapes and dtypes that
 * must be refused), and files built byte by byte to numpy's format for the
 * hostile cases, every truncation and random corruption. */
#include "reader_test_support.h"

/* Particle i's coordinate k in make_npy_fixtures.py. */
static double coordinate(uint64_t i, int k)
{
    return (double)(3 * i + (uint64_t)k) * 0.25 - 1.5;
}

/* "\x93NUMPY", version, header length, the dict padded with spaces and a newline to a multiple of 64. */
static void put_header(bytes *b, int major, const char *dict)
{
    size_t prefix = major == 1 ? 10 : 12;
    size_t len = strlen(dict) + 1;
    size_t padded = (prefix + len + 63) / 64 * 64 - prefix;
    bytes_append(b, "\x93NUMPY", 6);
    uint8_t version[2] = { (uint8_t)major, 0 };
    bytes_append(b, version, 2);
    bytes_uint(b, padded, major == 1 ? 2 : 4, false);
    bytes_append(b, dict, strlen(dict));
    for (size_t i = len; i < padded; i++)
        bytes_append(b, " ", 1);
    bytes_append(b, "\n", 1);
}

/* n particles of the formula, C or Fortran order, float32 or float64, either byte order. */
static bytes npy_file(int major, const char *descr, bool fortran, uint64_t n)
{
    bytes b = { NULL, 0, 0 };
    char dict[256];
    snprintf(dict, sizeof dict, "{'descr': '%s', 'fortran_order': %s, 'shape': (%llu, 3), }", descr,
             fortran ? "True" : "False", (unsigned long long)n);
    put_header(&b, major, dict);
    bool big = descr[0] == '>';
    for (uint64_t at = 0; at < 3 * n; at++) {
        uint64_t i = fortran ? at % n : at / 3;
        int k = (int)(fortran ? at / n : at % 3);
        if (descr[2] == '4')
            bytes_f32(&b, (float)coordinate(i, k), big);
        else
            bytes_f64(&b, coordinate(i, k), big);
    }
    return b;
}

static void check_formula(const fc_frame *f, uint64_t n, const char *what)
{
    CHECK_MSG(f->count == n && !f->density && !f->velocity && !f->ids, "%s: %llu particles", what,
              (unsigned long long)f->count);
    for (uint64_t i = 0; i < n && i < f->count; i++)
        check_position(f, i, (float)coordinate(i, 0), (float)coordinate(i, 1), (float)coordinate(i, 2));
}

static void test_built_files(void)
{
    static const struct { int major; const char *descr; bool fortran; } cases[] = {
        { 1, "<f4", false }, { 1, "<f8", false }, { 2, "<f4", false }, { 3, "<f8", false },
        { 1, "<f4", true },  { 1, ">f8", false }, { 1, ">f4", true },  { 1, "=f4", false },
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        bytes b = npy_file(cases[c].major, cases[c].descr, cases[c].fortran, 7);
        fc_frame frame;
        fc_error err = { FC_OK, "" };
        CHECK_MSG(fc_read_particles_mem(b.data, b.len, FC_FILE_NPY, "p.npy", &frame, &err) == FC_OK, "case %zu: %s", c,
                  err.message);
        check_formula(&frame, 7, cases[c].descr);
        fc_frame_free(&frame);
        bytes_free(&b);
    }
    /* Double quotes, no spaces, no trailing comma, Python 2's 7L: what other writers produce. */
    bytes b = { NULL, 0, 0 };
    put_header(&b, 1, "{\"descr\":\"<f4\",\"fortran_order\":False,\"shape\":(1L,3L)}");
    bytes_f32(&b, 1, false), bytes_f32(&b, 2, false), bytes_f32(&b, 3, false);
    fc_frame frame;
    fc_error err = { FC_OK, "" };
    CHECK_MSG(fc_read_particles_mem(b.data, b.len, FC_FILE_NPY, "q.npy", &frame, &err) == FC_OK, "%s", err.message);
    if (frame.count == 1)
        check_position(&frame, 0, 1, 2, 3);
    fc_frame_free(&frame);
    bytes_free(&b);
    CHECK(fc_file_format_from_path("positions.NPY") == FC_FILE_NPY);
}

static void expect_header_failure(const char *dict, const char *needle)
{
    bytes b = { NULL, 0, 0 };
    put_header(&b, 1, dict);
    for (int i = 0; i < 6; i++)
        bytes_f32(&b, 1, false);
    expect_failure(&b, FC_FILE_NPY, "h.npy", FC_ERR_PARSE, needle);
    bytes_free(&b);
}

static void test_refusals(void)
{
    expect_text_failure("PK\x03\x04 not an npy", FC_FILE_NPY, "a.npz.npy", "not a numpy .npy file");
    bytes b = { NULL, 0, 0 };
    bytes_append(&b, "\x93NUMPY\x04\x00\x10\x00", 10);
    expect_failure(&b, FC_FILE_NPY, "v4.npy", FC_ERR_PARSE, ".npy version 4.0 is not supported");
    bytes_free(&b);
    bytes_append(&b, "\x93NUMPY\x01\x00\xff\xff{}", 12);
    expect_failure(&b, FC_FILE_NPY, "len.npy", FC_ERR_PARSE, "header of 65535 bytes runs past the end of the data");
    bytes_free(&b);
    bytes_append(&b, "\x93NUMPY\x02\x00\xff\xff\xff\xff{}", 14);
    expect_failure(&b, FC_FILE_NPY, "len2.npy", FC_ERR_PARSE, "header of 4294967295 bytes runs past");
    bytes_free(&b);
    bytes_append(&b, "\x93NUMPY\x01", 7);
    expect_failure(&b, FC_FILE_NPY, "cut.npy", FC_ERR_PARSE, "file ends in the version");
    bytes_free(&b);

    expect_header_failure("[1, 2]", "header is not a dict");
    expect_header_failure("{'descr': '<f4', 'shape': (2, 3), }", "header lacks 'fortran_order'");
    expect_header_failure("{'descr': '<i4', 'fortran_order': False, 'shape': (2, 3), }",
                          "dtype '<i4' is not supported (float32 '<f4' or float64 '<f8')");
    expect_header_failure("{'descr': [('x', '<f4'), ('y', '<f4')], 'fortran_order': False, 'shape': (2,), }",
                          "'descr' is not a simple dtype string (structured arrays are not supported");
    expect_header_failure("{'descr': '<f4', 'fortran_order': 0, 'shape': (2, 3), }",
                          "'fortran_order' is neither True nor False");
    expect_header_failure("{'descr': '<f4', 'fortran_order': False, 'shape': (2, 4), }",
                          "shape (2, 4) is not (N, 3)");
    expect_header_failure("{'descr': '<f4', 'fortran_order': False, 'shape': (6,), }", "shape (6, ) is not (N, 3)");
    expect_header_failure("{'descr': '<f4', 'fortran_order': False, 'shape': (-2, 3), }",
                          "'shape' holds something other than non-negative integers");
    expect_header_failure("{'descr': '<f4', 'fortran_order': False, 'shape': (18446744073709551616, 3), }",
                          "'shape' holds something other than non-negative integers");
    expect_header_failure("{'descr': '<f4', 'fortran_order': False, 'shape': (4611686018427387904, 3), }",
                          "4611686018427387904 x 3 values of 4 bytes cannot fit in the 24 bytes left");
    expect_header_failure("{'descr': '<f4', 'fortran_order': False, 'shape': (0, 3), }", "no particles");
    expect_header_failure("{'descr': '<f4', 'fortran_order': False, 'shape': (1, 3), }",
                          "12 bytes after the array's 1 x 3 values");
    expect_header_failure("{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3), 'extra': 1}",
                          "unexpected key 'extra'");
    expect_header_failure("{'descr': '<f4' 'fortran_order': False}", "expected ',' or '}' after a value");
    expect_header_failure("{'descr': '<f4', 'fortran_order': False, 'shape': (1 2, 3)}",
                          "'shape' is not a tuple of integers");
    expect_header_failure("{'descr", "expected 'key': value");

    put_header(&b, 1, "{'descr': '<f4', 'fortran_order': False, 'shape': (1, 3), }");
    bytes_f32(&b, 1, false), bytes_f32(&b, NAN, false), bytes_f32(&b, 3, false);
    expect_failure(&b, FC_FILE_NPY, "nan.npy", FC_ERR_PARSE, "particle 0: y = nan");
    bytes_free(&b);
    put_header(&b, 1, "{'descr': '<f8', 'fortran_order': False, 'shape': (1, 3), }");
    bytes_f64(&b, 1, false), bytes_f64(&b, 2, false), bytes_f64(&b, 1e300, false);
    expect_failure(&b, FC_FILE_NPY, "big.npy", FC_ERR_PARSE, "particle 0: z = 1e+300 is not a finite value in float range");
    bytes_free(&b);
}

/* The files make_npy_fixtures.py wrote with numpy, when it could. */
static void test_numpy_files(const char *dir)
{
    static const char *const good[] = { "f32_v1.npy", "f64_v1.npy", "f32_v2.npy", "fortran.npy", "big_endian.npy" };
    static const struct { const char *name, *needle; } bad[] = {
        { "int32.npy", "dtype '<i4' is not supported" },
        { "structured.npy", "structured arrays are not supported" },
        { "flat.npy", "shape (3000, ) is not (N, 3)" },
        { "four_columns.npy", "shape (1000, 4) is not (N, 3)" },
    };
    char path[512];
    snprintf(path, sizeof path, "%s/%s", dir, good[0]);
    if (access(path, R_OK) != 0) {
        printf("no numpy-written files in %s (python3-numpy missing?): byte-built files only\n", dir);
        return;
    }
    for (size_t i = 0; i < sizeof good / sizeof good[0]; i++) {
        snprintf(path, sizeof path, "%s/%s", dir, good[i]);
        fc_frame frame;
        fc_error err = { FC_OK, "" };
        CHECK_MSG(fc_read_particles(path, &frame, &err) == FC_OK, "%s", err.message);
        check_formula(&frame, 1000, good[i]);
        fc_frame_free(&frame);
    }
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        snprintf(path, sizeof path, "%s/%s", dir, bad[i].name);
        fc_frame frame;
        fc_error err = { FC_OK, "" };
        CHECK_CODE(fc_read_particles(path, &frame, &err), FC_ERR_PARSE);
        CHECK_MSG(strstr(err.message, bad[i].needle) != NULL, "%s: '%s' lacks '%s'", bad[i].name, err.message,
                  bad[i].needle);
        CHECK(frame_is_empty(&frame));
    }
    printf("read %zu numpy-written files and refused %zu\n", sizeof good / sizeof good[0], sizeof bad / sizeof bad[0]);
}

static void test_truncations_and_mutations(void)
{
    bytes b = npy_file(1, "<f4", false, 3);
    check_truncations(&b, FC_FILE_NPY, b.len, 3);
    check_mutations(&b, FC_FILE_NPY, 3000, 17u);
    bytes_free(&b);
    b = npy_file(2, ">f8", true, 3);
    check_truncations(&b, FC_FILE_NPY, b.len, 3);
    check_mutations(&b, FC_FILE_NPY, 3000, 19u);
    bytes_free(&b);
}

int main(void)
{
    test_built_files();
    test_refusals();
    const char *fixtures = getenv("FC_NPY_FIXTURES");
    if (fixtures)
        test_numpy_files(fixtures);
    else
        printf("FC_NPY_FIXTURES not set: byte-built files only\n");
    test_truncations_and_mutations();
    return test_result();
}
