/* test_reader_vtkxml.c — VTK XML .vtu/.vtp and .pvd collections: every file
 * make_vtkxml_fixtures.py wrote with VTK's own writers (when python3-vtk9 is
 * there: ascii, inline binary, appended base64 and raw, zlib in several blocks,
 * UInt32 and UInt64 headers, Float32 and Float64 points, big-endian, a .pvd; and
 * legacy .vtk, ascii and binary, versions 4.2 and 5.1, for reader_vtk.c), and
 * files built byte by byte for the refusals, truncations and random corruption. */
#include <zlib.h>
#include "reader_test_support.h"

/* make_vtkxml_fixtures.py's particles. */
enum { FIXTURE_N = 300 };

static void check_fixture_frame(const fc_frame *f, const char *what)
{
    CHECK_MSG(f->count == FIXTURE_N && f->velocity && f->density && f->ids, "%s: %llu particles, v %d rho %d id %d",
              what, (unsigned long long)f->count, f->velocity != NULL, f->density != NULL, f->ids != NULL);
    if (!(f->count == FIXTURE_N && f->velocity && f->density && f->ids))
        return;
    int failures_before = test_failures_;
    for (uint64_t i = 0; i < FIXTURE_N && test_failures_ == failures_before; i++) {
        double d = (double)i;
        check_position(f, i, (float)(0.5 * d), (float)-d, (float)(2 * d + 0.25));
        check_velocity(f, i, (float)(3 * d / 8), (float)((3 * d + 1) / 8), (float)((3 * d + 2) / 8));
        CHECK_MSG(f->density[i] == (float)(1000 + d / 4) && f->ids[i] == 1000000 + i, "%s: particle %llu", what,
                  (unsigned long long)i);
    }
    if (test_failures_ != failures_before)
        fprintf(stderr, "in %s\n", what);
}

static void test_vtk_files(const char *dir)
{
    char path[512], line[256];
    snprintf(path, sizeof path, "%s/manifest.txt", dir);
    FILE *manifest = fopen(path, "r");
    if (manifest == NULL) {
        printf("no VTK-written files in %s (python3-vtk9 missing?): byte-built files only\n", dir);
        return;
    }
    int files = 0;
    while (fgets(line, sizeof line, manifest)) {
        line[strcspn(line, "\n")] = '\0';
        snprintf(path, sizeof path, "%s/%s", dir, line);
        fc_frame frame;
        fc_error err = { FC_OK, "" };
        CHECK_MSG(fc_read_particles(path, &frame, &err) == FC_OK, "%s", err.message);
        check_fixture_frame(&frame, line);
        fc_frame_free(&frame);
        files++;
    }
    fclose(manifest);
    CHECK(files >= 61);
    /* The collection stands for its first dataset, found relative to the .pvd. */
    snprintf(path, sizeof path, "%s/series.pvd", dir);
    fc_frame frame;
    fc_error err = { FC_OK, "" };
    CHECK_MSG(fc_read_particles(path, &frame, &err) == FC_OK, "%s", err.message);
    check_fixture_frame(&frame, "series.pvd");
    fc_frame_free(&frame);
    printf("read %d VTK-written files and a .pvd\n", files);
}

/* ---- byte-built files ---- */

#define HEAD(attrs) "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" " attrs ">\n"
#define PIECE(n) "<UnstructuredGrid>\n<Piece NumberOfPoints=\"" n "\" NumberOfCells=\"0\">\n"
#define TAIL "</Piece>\n</UnstructuredGrid>\n</VTKFile>\n"
#define POINTS_ASCII "<Points>\n<DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">\n1 2 3 4 5 6\n</DataArray>\n</Points>\n"

static const char GOOD_ASCII[] =
    HEAD("byte_order=\"LittleEndian\"") PIECE("2")
    "<PointData>\n<DataArray type=\"Float64\" Name=\"Density\" format=\"ascii\">\n998.5 1001.25\n"
    "<InformationKey name=\"x\">\n<Value>7 7 7</Value>\n</InformationKey>\n</DataArray>\n"
    "<DataArray type=\"UInt32\" Name=\"ParticleIds\" format=\"ascii\">4294967295 0</DataArray>\n"
    "<DataArray type=\"Float32\" Name=\"U\" NumberOfComponents=\"3\" format=\"ascii\">0 0 -9.75 1 2 3</DataArray>\n"
    "</PointData>\n" POINTS_ASCII TAIL;

static void test_ascii(void)
{
    fc_frame frame;
    fc_error err = { FC_OK, "" };
    CHECK_MSG(fc_read_particles_mem((const uint8_t *)GOOD_ASCII, strlen(GOOD_ASCII), FC_FILE_VTK_XML, "a.vtu", &frame,
                                    &err) == FC_OK, "%s", err.message);
    CHECK(frame.count == 2 && frame.density && frame.ids && frame.velocity);
    if (frame.count == 2 && frame.density && frame.ids && frame.velocity) {
        check_position(&frame, 0, 1, 2, 3);
        check_position(&frame, 1, 4, 5, 6);
        check_velocity(&frame, 0, 0, 0, -9.75f);
        CHECK(frame.density[0] == 998.5f && frame.density[1] == 1001.25f);
        CHECK(frame.ids[0] == 4294967295u && frame.ids[1] == 0);
    }
    fc_frame_free(&frame);
    CHECK(fc_file_format_from_path("a/b.VTP") == FC_FILE_VTK_XML && fc_file_format_from_path("s.pvd") == FC_FILE_PVD);
}

/* VTK's compressed block: nblocks, block size, last size, compressed sizes (UInt32), then the zlib streams. */
static void put_zlib_block(bytes *b, const void *data, size_t size, size_t block_size)
{
    size_t blocks = (size + block_size - 1) / block_size;
    bytes packed[8];
    bytes_uint(b, blocks, 4, false);
    bytes_uint(b, block_size, 4, false);
    bytes_uint(b, size % block_size, 4, false);
    for (size_t i = 0; i < blocks; i++) {
        size_t n = i + 1 == blocks ? size - i * block_size : block_size;
        uLongf len = compressBound(n);
        packed[i] = (bytes){ NULL, 0, 0 };
        bytes_append(&packed[i], NULL, 0);
        packed[i].data = malloc(len);
        CHECK(compress(packed[i].data, &len, (const Bytef *)data + i * block_size, n) == Z_OK);
        packed[i].len = len;
        bytes_uint(b, len, 4, false);
    }
    for (size_t i = 0; i < blocks; i++) {
        bytes_append(b, packed[i].data, packed[i].len);
        free(packed[i].data);
    }
}

/* Two particles, positions raw appended (optionally zlib in 8-byte blocks), then density at the next offset. */
static bytes raw_appended(bool zlib, size_t *data_end)
{
    static const float positions[6] = { 1, 2, 3, 4, 5, 6 };
    static const float density[2] = { 999, 1001 };
    bytes data = { NULL, 0, 0 };
    if (zlib) {
        put_zlib_block(&data, positions, sizeof positions, 8);
    } else {
        bytes_uint(&data, sizeof positions, 4, false);
        for (int i = 0; i < 6; i++)
            bytes_f32(&data, positions[i], false);
    }
    size_t second = data.len;
    if (zlib) {
        put_zlib_block(&data, density, sizeof density, 8);
    } else {
        bytes_uint(&data, sizeof density, 4, false);
        bytes_f32(&data, density[0], false), bytes_f32(&data, density[1], false);
    }
    bytes b = { NULL, 0, 0 };
    bytes_printf(&b, HEAD("byte_order=\"LittleEndian\" header_type=\"UInt32\"%s") PIECE("2"),
                 zlib ? " compressor=\"vtkZLibDataCompressor\"" : "");
    bytes_printf(&b, "<PointData>\n<DataArray type=\"Float32\" Name=\"rho\" format=\"appended\" offset=\"%zu\"/>\n"
                     "</PointData>\n<Points>\n<DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"appended\" "
                     "offset=\"0\"/>\n</Points>\n</Piece>\n</UnstructuredGrid>\n<AppendedData encoding=\"raw\">\n   _",
                 second);
    bytes_append(&b, data.data, data.len);
    *data_end = b.len;
    bytes_printf(&b, "\n</AppendedData>\n</VTKFile>\n");
    bytes_free(&data);
    return b;
}

static void test_raw_appended(void)
{
    for (int zlib = 0; zlib < 2; zlib++) {
        size_t data_end;
        bytes b = raw_appended(zlib, &data_end);
        fc_frame frame;
        fc_error err = { FC_OK, "" };
        CHECK_MSG(fc_read_particles_mem(b.data, b.len, FC_FILE_VTK_XML, "r.vtu", &frame, &err) == FC_OK, "%s",
                  err.message);
        CHECK(frame.count == 2 && frame.density && !frame.velocity);
        if (frame.count == 2 && frame.density) {
            check_position(&frame, 1, 4, 5, 6);
            CHECK(frame.density[0] == 999 && frame.density[1] == 1001);
        }
        fc_frame_free(&frame);
        check_truncations(&b, FC_FILE_VTK_XML, data_end, 2);
        check_mutations(&b, FC_FILE_VTK_XML, 3000, 23u + (uint32_t)zlib);
        bytes_free(&b);
    }
}

static void expect_vtu_failure(const char *text, const char *needle)
{
    expect_text_failure(text, FC_FILE_VTK_XML, "bad.vtu", needle);
}

static void test_refusals(void)
{
    expect_vtu_failure("<?xml version=\"1.0\"?>\n<Foo/>\n", "line 2: root element 'Foo' is not VTKFile");
    expect_vtu_failure("<VTKFile type=\"ImageData\"></VTKFile>", "VTKFile type 'ImageData' is not a particle dataset");
    expect_vtu_failure("<VTKFile type=\"Collection\"></VTKFile>", "a .pvd collection, not a dataset");
    expect_vtu_failure(HEAD("compressor=\"vtkLZ4DataCompressor\"") PIECE("2") POINTS_ASCII TAIL,
                       "compressor 'vtkLZ4DataCompressor' is not supported");
    expect_vtu_failure(HEAD("header_type=\"UInt16\"") PIECE("2") POINTS_ASCII TAIL, "header_type 'UInt16'");
    expect_vtu_failure(HEAD("byte_order=\"Middle\"") PIECE("2") POINTS_ASCII TAIL, "byte_order 'Middle'");
    expect_vtu_failure(HEAD("") PIECE("2") POINTS_ASCII "</Piece>\n<Piece NumberOfPoints=\"1\">" TAIL,
                       "a second Piece");
    expect_vtu_failure(HEAD("") PIECE("2") TAIL, "no Piece with Points found");
    expect_vtu_failure(HEAD("") PIECE("-2") POINTS_ASCII TAIL, "Piece lacks a non-negative integer NumberOfPoints");
    expect_vtu_failure(HEAD("") PIECE("0") POINTS_ASCII TAIL, "no particles");
    expect_vtu_failure(HEAD("") PIECE("3") POINTS_ASCII TAIL, "DataArray 'Points': 6 values, expected 9");
    expect_vtu_failure(HEAD("") PIECE("1") POINTS_ASCII TAIL, "DataArray 'Points': more than the 3 values expected");
    expect_vtu_failure(HEAD("") PIECE("1000000000000")
                       "<Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">1 2 3</DataArray></Points>" TAIL,
                       "NumberOfPoints 1000000000000 x 3 components cannot fit in its data");
    expect_vtu_failure(HEAD("") PIECE("1")
                       "<Points><DataArray type=\"Float32\" NumberOfComponents=\"2\" format=\"ascii\">1 2</DataArray></Points>" TAIL,
                       "DataArray 'Points' has 2 components, Points needs 3");
    expect_vtu_failure(HEAD("") PIECE("1")
                       "<Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">1 2 x</DataArray></Points>" TAIL,
                       "'x' is not a number");
    expect_vtu_failure(HEAD("") PIECE("1")
                       "<Points><DataArray type=\"String\" NumberOfComponents=\"3\" format=\"ascii\">1 2 3</DataArray></Points>" TAIL,
                       "type 'String' is not a numeric VTK type");
    expect_vtu_failure(HEAD("") PIECE("1")
                       "<Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"hex\">1 2 3</DataArray></Points>" TAIL,
                       "format 'hex' is not ascii, binary or appended");
    expect_vtu_failure(HEAD("") PIECE("1")
                       "<Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"appended\" offset=\"0\"/></Points>" TAIL,
                       "is appended but the file has no AppendedData");
    expect_vtu_failure(HEAD("") PIECE("1") "<PointData><DataArray type=\"Float32\" Name=\"v\" format=\"ascii\">1</DataArray>"
                       "</PointData>" POINTS_ASCII TAIL, "DataArray 'v' has 1 components, vx needs 3");
    expect_vtu_failure(HEAD("") PIECE("1") "<PointData><DataArray type=\"Float32\" Name=\"rho\" format=\"ascii\">1</DataArray>"
                       "<DataArray type=\"Float32\" Name=\"density\" format=\"ascii\">1</DataArray></PointData>" POINTS_ASCII TAIL,
                       "DataArray 'density' gives density a second time");
    expect_vtu_failure(HEAD("") PIECE("1") "<PointData><DataArray type=\"Int32\" Name=\"id\" format=\"ascii\">-1</DataArray>"
                       "</PointData><Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">1 2 3</DataArray></Points>" TAIL,
                       "DataArray 'id': particle 0: id = -1 is not an integer");
    expect_vtu_failure(HEAD("") PIECE("1") "<Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"binary\">"
                       "DAAAAAAAgD8AAABAAABAQA=!</DataArray></Points>" TAIL, "invalid base64 text in the data");
    expect_vtu_failure(HEAD("") PIECE("1") "<Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"binary\">"
                       "CAAAAAAAgD8AAABAAABAQA==</DataArray></Points>" TAIL, "header says 8 bytes, the array holds 12");
    expect_vtu_failure(HEAD("") PIECE("1") "<Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"binary\">"
                       "DAAAAAAAgD8AAABA</DataArray></Points>" TAIL, "data ends in the data");
    expect_vtu_failure(HEAD("compressor=\"vtkZLibDataCompressor\"") PIECE("1")
                       "<Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"binary\">"
                       "AQAAAACAAAAIAAAAFAAAAA==eJxjYACBBnsGBgAGwQHB</DataArray></Points>" TAIL,
                       "1 blocks of 32768 bytes (last 8) do not make the array's 12 bytes");
    expect_vtu_failure(HEAD("") PIECE("1") "<Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">1 2 3",
                       "XML: ");
    expect_vtu_failure(HEAD("") PIECE("1") POINTS_ASCII "</Piece></UnstructuredGrid>\n<AppendedData encoding=\"raw\">junk",
                       "AppendedData does not start with '_'");
    expect_vtu_failure(HEAD("") PIECE("1") "<Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"appended\" "
                       "offset=\"99\"/></Points></Piece></UnstructuredGrid>\n<AppendedData encoding=\"raw\">_abcdefghijklmnop",
                       "offset 99 is past the appended data's 16 bytes");
    expect_vtu_failure(HEAD("") PIECE("1") "<Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"appended\" "
                       "offset=\"0\"/></Points></Piece></UnstructuredGrid>\n<AppendedData encoding=\"raw\">_\x0c\x01\x02",
                       "NumberOfPoints 1 x 3 components cannot fit in its data (at most 0 values)");
    expect_vtu_failure(HEAD("") PIECE("1") "<Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"appended\" "
                       "offset=\"0\"/></Points></Piece></UnstructuredGrid>\n<AppendedData encoding=\"uuencode\">_",
                       "AppendedData encoding 'uuencode' is neither raw nor base64");

    /* A collection read from memory cannot reach its files. */
    expect_text_failure("<VTKFile type=\"Collection\"><Collection><DataSet file=\"a.vtu\"/></Collection></VTKFile>",
                        FC_FILE_PVD, "s.pvd", "a .pvd collection names other files");
}

/* .pvd files on disk: no DataSet, a DataSet that is missing, a nested .pvd, a broken first dataset. */
static void test_pvd_refusals(void)
{
    static const struct { const char *text, *needle; } cases[] = {
        { "<VTKFile type=\"Collection\"><Collection></Collection></VTKFile>", "the collection lists no DataSet" },
        { "<VTKFile type=\"UnstructuredGrid\"></VTKFile>", "not a .pvd collection" },
        { "<VTKFile type=\"Collection\"><Collection><DataSet timestep=\"0\"/></Collection></VTKFile>",
          "DataSet without a file attribute" },
        { "<VTKFile type=\"Collection\"><Collection><DataSet file=\"other.pvd\"/></Collection></VTKFile>",
          "first DataSet 'other.pvd' is not a particle file" },
        { "<VTKFile type=\"Collection\"><Collection><DataSet file=\"missing.vtu\"/></Collection></VTKFile>",
          "its first DataSet: " },
        { "<VTKFile type=\"Collection\"><Collection><DataSet file=\"broken.vtu\"/></Collection></VTKFile>",
          "broken.vtu: line 1: root element 'Foo' is not VTKFile" },
        { "<VTKFile type=\"Collection\"><Collection>", "XML: " },
    };
    bytes broken = { NULL, 0, 0 };
    bytes_printf(&broken, "<Foo/>");
    write_temp_file("broken.vtu", &broken);
    bytes_free(&broken);
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        bytes b = { NULL, 0, 0 };
        bytes_printf(&b, "%s", cases[i].text);
        const char *path = write_temp_file("s.pvd", &b);
        fc_frame frame;
        fc_error err = { FC_OK, "" };
        CHECK_CODE(fc_read_particles(path, &frame, &err), i == 4 ? FC_ERR_IO : FC_ERR_PARSE);
        CHECK_MSG(strstr(err.message, path) == err.message && strstr(err.message, cases[i].needle),
                  "'%s' lacks '%s'", err.message, cases[i].needle);
        CHECK(frame_is_empty(&frame));
        bytes_free(&b);
    }
    remove_temp_file("s.pvd");
    remove_temp_file("broken.vtu");
}

static void test_ascii_truncations_and_mutations(void)
{
    bytes b = { NULL, 0, 0 };
    bytes_append(&b, GOOD_ASCII, strlen(GOOD_ASCII));
    check_truncations(&b, FC_FILE_VTK_XML, b.len - 1, 2);
    check_mutations(&b, FC_FILE_VTK_XML, 3000, 29u);
    bytes_free(&b);
}

int main(void)
{
    test_ascii();
    test_raw_appended();
    test_refusals();
    test_pvd_refusals();
    test_ascii_truncations_and_mutations();
    const char *fixtures = getenv("FC_VTKXML_FIXTURES");
    if (fixtures)
        test_vtk_files(fixtures);
    else
        printf("FC_VTKXML_FIXTURES not set: byte-built files only\n");
    remove_temp_dir();
    return test_result();
}
