/* test_reader_bgeo.c — Houdini classic BGEO (V5) as partio writes it, built byte
 * by byte from the format's layout (big-endian header, point attribute
 * definitions, x y z w plus attributes per point, partio's trailing 00 ff), plain
 * and gzip'd under the .bgeo name; the newer formats refused with advice; every
 * truncation and random corruption of both. */
#include <zlib.h>
#include "reader_test_support.h"

static const float X[3][3] = { { 0.5f, -1.25f, 3.0f }, { -0.001f, 2000.0f, 0.015f }, { 10.0f, 20.0f, 30.0f } };
static const float DENSITY[3] = { 1000.5f, 998.25f, 1001.0f };
static const float V[3][3] = { { 0.125f, -0.25f, 4.0f }, { 0.0f, 0.0f, -9.81f }, { 1.0f, 2.0f, 3.0f } };
static const int32_t IDS[3] = { 7, 2147483647, 0 };

enum { T_FLOAT = 0, T_INT = 1, T_INDEX = 4, T_VECTOR = 5 };

static void put_i32(bytes *b, int64_t v) { bytes_uint(b, (uint64_t)v, 4, true); }
static void put_u16(bytes *b, unsigned v) { bytes_uint(b, v, 2, true); }

static void put_string(bytes *b, const char *s)
{
    put_u16(b, (unsigned)strlen(s));
    bytes_append(b, s, strlen(s));
}

/* "Bgeo" 'V' version nPoints nPrims nPointGroups nPrimGroups nPointAttrib nVertexAttrib nPrimAttrib nAttrib */
static void put_header(bytes *b, int32_t version, int64_t points, int32_t attributes)
{
    bytes_append(b, "BgeoV", 5);
    put_i32(b, version);
    put_i32(b, points);
    for (int i = 0; i < 3; i++)
        put_i32(b, 0);
    put_i32(b, attributes);
    for (int i = 0; i < 3; i++)
        put_i32(b, 0);
}

/* A float/int/vector attribute with zero defaults, as partio writes them. */
static void put_attribute(bytes *b, const char *name, unsigned components, int32_t type)
{
    put_string(b, name);
    put_u16(b, components);
    put_i32(b, type);
    for (unsigned k = 0; k < components; k++)
        put_i32(b, 0);
}

static void put_index_attribute(bytes *b, const char *name)
{
    put_string(b, name);
    put_u16(b, 1);
    put_i32(b, T_INDEX);
    put_i32(b, 2);
    put_string(b, "fluid");
    put_string(b, "boundary");
}

/* Three particles with Cd (skipped), v, density, id and an index attribute (skipped). */
static bytes full_file(size_t *points_end)
{
    bytes b = { NULL, 0, 0 };
    put_header(&b, 5, 3, 5);
    put_attribute(&b, "Cd", 3, T_VECTOR);
    put_attribute(&b, "v", 3, T_VECTOR);
    put_attribute(&b, "density", 1, T_FLOAT);
    put_index_attribute(&b, "phase");
    put_attribute(&b, "id", 1, T_INT);
    for (int i = 0; i < 3; i++) {
        for (int k = 0; k < 3; k++)
            bytes_f32(&b, X[i][k], true);
        bytes_f32(&b, 1.0f, true);
        for (int k = 0; k < 3; k++)
            bytes_f32(&b, 0.5f, true);
        for (int k = 0; k < 3; k++)
            bytes_f32(&b, V[i][k], true);
        bytes_f32(&b, DENSITY[i], true);
        put_i32(&b, i % 2);
        put_i32(&b, IDS[i]);
    }
    *points_end = b.len;
    bytes_append(&b, "\x00\xff", 2); /* partio's beginExtra / endExtra */
    return b;
}

static bytes gzip(const bytes *plain)
{
    z_stream z = { 0 };
    CHECK(deflateInit2(&z, 6, Z_DEFLATED, 16 + MAX_WBITS, 8, Z_DEFAULT_STRATEGY) == Z_OK);
    bytes out = { NULL, 0, 0 };
    uint8_t buffer[4096];
    z.next_in = plain->data;
    z.avail_in = (uInt)plain->len;
    int status;
    do {
        z.next_out = buffer;
        z.avail_out = sizeof buffer;
        status = deflate(&z, Z_FINISH);
        bytes_append(&out, buffer, sizeof buffer - z.avail_out);
    } while (status == Z_OK);
    CHECK(status == Z_STREAM_END);
    deflateEnd(&z);
    return out;
}

static void check_full_frame(const fc_frame *f)
{
    CHECK(f->count == 3 && f->density && f->velocity && f->ids);
    if (!(f->count == 3 && f->density && f->velocity && f->ids))
        return;
    for (int i = 0; i < 3; i++) {
        check_position(f, (uint64_t)i, X[i][0], X[i][1], X[i][2]);
        check_velocity(f, (uint64_t)i, V[i][0], V[i][1], V[i][2]);
        CHECK(f->density[i] == DENSITY[i]);
        CHECK(f->ids[i] == (uint32_t)IDS[i]);
    }
}

static void test_good_files(void)
{
    size_t points_end;
    bytes plain = full_file(&points_end);
    bytes packed = gzip(&plain);
    fc_frame frame;
    fc_error err = { FC_OK, "" };
    CHECK_CODE(fc_read_particles_mem(plain.data, plain.len, FC_FILE_BGEO, "f.bgeo", &frame, &err), FC_OK);
    check_full_frame(&frame);
    fc_frame_free(&frame);
    /* gzip'd under the .bgeo name, read from disk: recognised by its magic bytes. */
    const char *path = write_temp_file("frame_0001.bgeo", &packed);
    CHECK_MSG(fc_read_particles(path, &frame, &err) == FC_OK, "%s", err.message);
    check_full_frame(&frame);
    fc_frame_free(&frame);
    remove_temp_file("frame_0001.bgeo");
    bytes_free(&plain);
    bytes_free(&packed);
}

/* Positions only, then "velocity" spelled out with a float id: the attribute mask follows the file. */
static void test_attribute_variants(void)
{
    bytes b = { NULL, 0, 0 };
    put_header(&b, 5, 1, 0);
    bytes_f32(&b, 1, true), bytes_f32(&b, 2, true), bytes_f32(&b, 3, true), bytes_f32(&b, 1, true);
    fc_frame frame;
    fc_error err = { FC_OK, "" };
    CHECK_CODE(fc_read_particles_mem(b.data, b.len, FC_FILE_BGEO, "p.bgeo", &frame, &err), FC_OK);
    CHECK(frame.count == 1 && !frame.velocity && !frame.density && !frame.ids);
    check_position(&frame, 0, 1, 2, 3);
    fc_frame_free(&frame);
    bytes_free(&b);

    put_header(&b, 5, 1, 2);
    put_attribute(&b, "velocity", 3, T_FLOAT);
    put_attribute(&b, "id", 1, T_FLOAT);
    bytes_f32(&b, 1, true), bytes_f32(&b, 2, true), bytes_f32(&b, 3, true), bytes_f32(&b, 1, true);
    bytes_f32(&b, 4, true), bytes_f32(&b, 5, true), bytes_f32(&b, 6, true), bytes_f32(&b, 42, true);
    CHECK_CODE(fc_read_particles_mem(b.data, b.len, FC_FILE_BGEO, "v.bgeo", &frame, &err), FC_OK);
    CHECK(frame.count == 1 && frame.velocity && !frame.density && frame.ids);
    if (frame.velocity && frame.ids) {
        check_velocity(&frame, 0, 4, 5, 6);
        CHECK(frame.ids[0] == 42);
    }
    fc_frame_free(&frame);
    bytes_free(&b);
}

static void test_formats_from_names(void)
{
    CHECK(fc_file_format_from_path("out/ParticleData_Fluid_1.bgeo") == FC_FILE_BGEO);
    CHECK(fc_file_format_from_path("A.BGEO") == FC_FILE_BGEO);
    CHECK(fc_file_format_from_path("a.bgeo.gz") == FC_FILE_BGEO);
    CHECK(fc_file_format_from_path("a.bhclassic") == FC_FILE_BGEO);
    CHECK(fc_file_format_from_path("a.bgeo.sc") == FC_FILE_BGEO);
    CHECK(fc_file_format_from_path("a.sc") == FC_FILE_UNKNOWN);
    CHECK(fc_file_format_from_path("a.gz") == FC_FILE_UNKNOWN);
}

/* A header and one attribute definition followed by the bytes of one point. */
static void expect_attribute_failure(const char *name, unsigned components, int32_t type, const char *needle)
{
    bytes b = { NULL, 0, 0 };
    put_header(&b, 5, 1, 1);
    put_attribute(&b, name, components, type);
    for (unsigned k = 0; k < 4 + components; k++)
        bytes_f32(&b, 1, true);
    expect_failure(&b, FC_FILE_BGEO, "a.bgeo", FC_ERR_PARSE, needle);
    bytes_free(&b);
}

/* pscale (Houdini's point scale, as partio writes it) is each particle's radius; one that is not a
 * usable radius is refused naming the particle. */
static void test_pscale_is_the_radius(void)
{
    const float pscale[2] = { 0.025f, 0.05f };
    bytes b = { NULL, 0, 0 };
    put_header(&b, 5, 2, 1);
    put_attribute(&b, "pscale", 1, T_FLOAT);
    for (int i = 0; i < 2; i++) {
        bytes_f32(&b, (float)i, true), bytes_f32(&b, 0, true), bytes_f32(&b, 0, true), bytes_f32(&b, 1, true);
        bytes_f32(&b, pscale[i], true);
    }
    fc_frame frame;
    fc_error err = { FC_OK, "" };
    CHECK_CODE(fc_read_particles_mem(b.data, b.len, FC_FILE_BGEO, "r.bgeo", &frame, &err), FC_OK);
    CHECK(frame.count == 2 && frame.radius && fc_frame_attributes(&frame) == FC_ATTR_RADIUS);
    if (frame.radius)
        CHECK(frame.radius[0] == pscale[0] && frame.radius[1] == pscale[1]);
    fc_frame_free(&frame);
    /* The second particle's pscale 0: refused at its bytes, the particle named. */
    b.len -= 4;
    bytes_f32(&b, 0.0f, true);
    expect_failure(&b, FC_FILE_BGEO, "r.bgeo", FC_ERR_PARSE, "particle 1: radius = 0 is not a radius in (0, 1e6]");
    bytes_free(&b);
    expect_attribute_failure("pscale", 3, T_VECTOR, "radius needs 1 numbers");
}

static void test_refusals(void)
{
    bytes b = { NULL, 0, 0 };
    bytes_append(&b, "\x7fNSJb[", 6);
    expect_failure(&b, FC_FILE_BGEO, "new.bgeo", FC_ERR_PARSE, "binary JSON BGEO");
    expect_failure(&b, FC_FILE_BGEO, "new.bgeo", FC_ERR_PARSE, "export classic BGEO instead: save as .bhclassic");
    bytes_free(&b);
    bytes_append(&b, "\x02\x01\x21\x04whatever", 12);
    expect_failure(&b, FC_FILE_BGEO, "frame.bgeo.sc", FC_ERR_PARSE, "blosc-compressed BGEO (.bgeo.sc) is not supported");
    expect_failure(&b, FC_FILE_BGEO, "frame.bgeo", FC_ERR_PARSE, "not a classic BGEO file");
    bytes_free(&b);
    bytes_printf(&b, "PGEOMETRY V5\nNPoints 1 NPrims 0\n");
    expect_failure(&b, FC_FILE_BGEO, "ascii.bgeo", FC_ERR_PARSE, "ASCII Houdini geometry");
    bytes_free(&b);

    put_header(&b, 4, 1, 0);
    expect_failure(&b, FC_FILE_BGEO, "v4.bgeo", FC_ERR_PARSE, "classic BGEO version 4 is not supported");
    bytes_free(&b);
    put_header(&b, 5, -1, 0);
    expect_failure(&b, FC_FILE_BGEO, "neg.bgeo", FC_ERR_PARSE, "nPoints is negative (-1)");
    bytes_free(&b);
    put_header(&b, 5, 2147483647, 0);
    bytes_f32(&b, 1, true), bytes_f32(&b, 2, true), bytes_f32(&b, 3, true), bytes_f32(&b, 1, true);
    expect_failure(&b, FC_FILE_BGEO, "big.bgeo", FC_ERR_PARSE, "2147483647 points of 16 bytes cannot fit in the 16 bytes left");
    bytes_free(&b);
    put_header(&b, 5, 0, 0);
    expect_failure(&b, FC_FILE_BGEO, "none.bgeo", FC_ERR_PARSE, "no particles");
    bytes_free(&b);
    put_header(&b, 5, 1, 100000);
    expect_failure(&b, FC_FILE_BGEO, "many.bgeo", FC_ERR_PARSE, "100000 point attributes (at most 256)");
    bytes_free(&b);

    expect_attribute_failure("temperature", 1, 7, "point attribute 'temperature': unsupported type 7");
    expect_attribute_failure("v", 1, T_FLOAT, "point attribute 'v' has 1 numeric components, vx needs 3 numbers");
    expect_attribute_failure("density", 3, T_VECTOR, "point attribute 'density' has 3 numeric components");
    expect_attribute_failure("empty", 0, T_FLOAT, "point attribute 'empty' has no components");

    /* Two attributes that both give the velocity; an id that is no id. */
    put_header(&b, 5, 1, 2);
    put_attribute(&b, "v", 3, T_VECTOR);
    put_attribute(&b, "vel", 3, T_VECTOR);
    expect_failure(&b, FC_FILE_BGEO, "dup.bgeo", FC_ERR_PARSE, "point attribute 'vel' gives vx a second time");
    bytes_free(&b);
    put_header(&b, 5, 1, 1);
    put_attribute(&b, "id", 1, T_INT);
    bytes_f32(&b, 1, true), bytes_f32(&b, 2, true), bytes_f32(&b, 3, true), bytes_f32(&b, 1, true);
    put_i32(&b, -5);
    expect_failure(&b, FC_FILE_BGEO, "id.bgeo", FC_ERR_PARSE, "particle 0: id = -5 is not an integer");
    bytes_free(&b);
}

static void test_gzip_refusals(void)
{
    size_t points_end;
    bytes plain = full_file(&points_end);
    bytes packed = gzip(&plain);
    bytes_append(&packed, "junk", 4);
    expect_failure(&packed, FC_FILE_BGEO, "tail.bgeo", FC_ERR_PARSE, "gzip: 4 bytes after the end of the compressed stream");
    packed.len -= 4 + 20; /* into the deflate data */
    expect_failure(&packed, FC_FILE_BGEO, "cut.bgeo", FC_ERR_PARSE, "gzip: compressed stream is truncated");
    bytes_free(&packed);
    /* A gzip'd file that is not BGEO, and one cut short inside: both say the data was inflated. */
    plain.len = points_end - 3;
    packed = gzip(&plain);
    expect_failure(&packed, FC_FILE_BGEO, "short.bgeo", FC_ERR_PARSE, "gzip'd BGEO, after inflating: byte offset");
    bytes_free(&packed);
    bytes_free(&plain);
    /* A gzip header, then a deflate block of the reserved type 3. */
    bytes_append(&plain, "\x1f\x8b\x08\x00\x00\x00\x00\x00\x00\x03\x07\x00\x00\x00", 14);
    expect_failure(&plain, FC_FILE_BGEO, "bad.bgeo", FC_ERR_PARSE, "gzip: corrupt compressed data (invalid block type)");
    bytes_free(&plain);
}

static void test_truncations_and_mutations(void)
{
    size_t points_end;
    bytes plain = full_file(&points_end);
    check_truncations(&plain, FC_FILE_BGEO, points_end, 3);
    check_mutations(&plain, FC_FILE_BGEO, 3000, 11u);
    bytes packed = gzip(&plain);
    check_truncations(&packed, FC_FILE_BGEO, packed.len, 3);
    check_mutations(&packed, FC_FILE_BGEO, 3000, 13u);
    bytes_free(&packed);
    bytes_free(&plain);
}

int main(void)
{
    test_good_files();
    test_attribute_variants();
    test_pscale_is_the_radius();
    test_formats_from_names();
    test_refusals();
    test_gzip_refusals();
    test_truncations_and_mutations();
    remove_temp_dir();
    return test_result();
}
