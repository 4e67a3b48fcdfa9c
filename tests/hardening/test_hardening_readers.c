/* test_hardening_readers.c — one table of broken particle files for every
 * reader: truncated headers, counts larger than the data, counts that overflow
 * (2^62, 2^64 - 1, 2^64), garbage numbers, wrong property types. Each must be
 * refused with FC_ERR_PARSE, a message that starts with the file's name (or
 * path) and names the reason, and no frame; the sanitizer build (FC_SANITIZE)
 * turns any out-of-bounds read or leak on these paths into a failure.
 *
 * Complements tests/readers, which sweeps truncations and mutations of good files. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fc_frame.h"
#include "particle_reader.h"
#include "test_util.h"

typedef struct broken_file {
    const char *name;      /* its extension selects the reader */
    const char *bytes;
    size_t size;           /* 0: strlen(bytes) */
    const char *reason;    /* the message must contain this */
} broken_file;

/* A literal with NUL bytes in it: its size without the terminating NUL. */
#define BIN(literal) literal, sizeof literal - 1

#define PLY_XYZ "property float x\nproperty float y\nproperty float z\n"
#define PLY_ASCII "ply\nformat ascii 1.0\n"
#define PLY_LE "ply\nformat binary_little_endian 1.0\n"
#define ONE_LE_PARTICLE "\x00\x00\x80\x3f" "\x00\x00\x00\x40" "\x00\x00\x40\x40"   /* 1 2 3 */
#define VTK_ASCII "# vtk DataFile Version 3.0\nbroken\nASCII\nDATASET POLYDATA\n"
#define VTK_BINARY "# vtk DataFile Version 3.0\nbroken\nBINARY\nDATASET POLYDATA\n"
#define VTU_HEAD "<VTKFile type=\"UnstructuredGrid\"><UnstructuredGrid>"
#define VTU_ZLIB_HEAD "<VTKFile type=\"UnstructuredGrid\" compressor=\"vtkZLibDataCompressor\"><UnstructuredGrid>"
#define VTU_POINTS(format) "<Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"" format "\">"
#define VTU_TAIL "</DataArray></Points></Piece></UnstructuredGrid></VTKFile>"
#define NEST16 "<a><a><a><a><a><a><a><a><a><a><a><a><a><a><a><a>"
#define BGEO_ZEROS(n) BGEO_ZEROS_##n
#define BGEO_ZEROS_3 "\0\0\0\0\0\0\0\0\0\0\0\0"
#define BGEO_ZEROS_6 BGEO_ZEROS_3 BGEO_ZEROS_3
#define ONE_BE_PARTICLE "\x3f\x80\x00\x00" "\x40\x00\x00\x00" "\x40\x40\x00\x00"   /* 1 2 3 */

static const broken_file files[] = {
    /* ---- PLY ---- */
    {"empty.ply", "", 0, "empty file"},
    {"magic_cut.ply", "pl", 0, "not a PLY file"},
    {"header_cut.ply", PLY_LE "element vertex 1\nproperty float x\n", 0, "header ends without end_header"},
    {"header_cut_in_type.ply", PLY_LE "element vertex 1\nproperty flo", 0, "unknown property type 'flo'"},
    {"header_no_newline.ply", PLY_ASCII "element vertex 1\n" PLY_XYZ "end_header", 0, "1 instances cannot fit in the 0 bytes"},
    {"vertex_2_62_ascii.ply", PLY_ASCII "element vertex 4611686018427387904\n" PLY_XYZ "end_header\n1 2 3\n", 0,
     "4611686018427387904 instances cannot fit"},
    {"vertex_2_62_binary.ply", BIN(PLY_LE "element vertex 4611686018427387904\n" PLY_XYZ "end_header\n" ONE_LE_PARTICLE),
     "4611686018427387904 instances cannot fit"},
    {"vertex_u64_max.ply", BIN(PLY_LE "element vertex 18446744073709551615\n" PLY_XYZ "end_header\n" ONE_LE_PARTICLE),
     "18446744073709551615 instances cannot fit"},
    {"vertex_2_64.ply", BIN(PLY_LE "element vertex 18446744073709551616\n" PLY_XYZ "end_header\n" ONE_LE_PARTICLE),
     "element count '18446744073709551616' is not a non-negative integer"},
    {"vertex_negative.ply", PLY_ASCII "element vertex -1\n" PLY_XYZ "end_header\n1 2 3\n", 0,
     "element count '-1' is not a non-negative integer"},
    {"face_2_62.ply",
     BIN(PLY_LE "element vertex 1\n" PLY_XYZ "element face 4611686018427387904\nproperty list uchar int v\n"
                "end_header\n" ONE_LE_PARTICLE "\x00"),
     "element 'face': 4611686018427387904 instances cannot fit"},
    {"list_u32_max_binary.ply",
     BIN(PLY_LE "element vertex 1\n" PLY_XYZ "element face 1\nproperty list uint int v\nend_header\n" ONE_LE_PARTICLE
                "\xff\xff\xff\xff" "\x00\x00\x00\x00"),
     "items run past the end of the data"},
    {"list_negative_binary.ply",
     BIN(PLY_LE "element vertex 1\n" PLY_XYZ "element face 1\nproperty list int int v\nend_header\n" ONE_LE_PARTICLE
                "\xff\xff\xff\xff"),
     "count -1 is not a valid length"},
    {"list_fraction_binary.ply",
     BIN(PLY_LE "element vertex 1\n" PLY_XYZ "element face 1\nproperty list float int v\nend_header\n" ONE_LE_PARTICLE
                "\x00\x00\x20\x40"),
     "count 2.5 is not a valid length"},
    {"list_2_62_ascii.ply",
     PLY_ASCII "element vertex 1\n" PLY_XYZ "element face 1\nproperty list uint int v\nend_header\n1 2 3\n"
               "4611686018427387904 1 2\n", 0, "expected 4611686018427387905 values, found 3"},
    {"vertices_beyond_data_ascii.ply", PLY_ASCII "element vertex 5\n" PLY_XYZ "end_header\n1 2 3\n4 5 6\n7 8 9\n", 0,
     "data ends after 3 of 5 'vertex' lines"},
    {"vertices_beyond_data_binary.ply",
     BIN(PLY_LE "element vertex 2\n" PLY_XYZ "end_header\n" ONE_LE_PARTICLE "\x00\x00"),
     "2 instances cannot fit in the 14 bytes"},
    {"garbage_number.ply", PLY_ASCII "element vertex 1\n" PLY_XYZ "end_header\n1 2..0 3\n", 0,
     "y: '2..0' is not a number"},
    {"garbage_bytes.ply", BIN(PLY_ASCII "element vertex 1\n" PLY_XYZ "end_header\n1 \xff\xfe 3\n"),
     "y: '?\?' is not a number"},
    {"nul_in_number.ply", BIN(PLY_ASCII "element vertex 1\n" PLY_XYZ "end_header\n1 2\0 3\n"), "is not a number"},
    {"double_overflow.ply", PLY_ASCII "element vertex 1\n" PLY_XYZ "end_header\n1 2 1e400\n", 0,
     "particle 0: z"},
    {"x_is_list.ply", PLY_ASCII "element vertex 1\nproperty list uchar float x\nproperty float y\nproperty float z\n"
                      "end_header\n1 1 2 3\n", 0, "vertex property 'x' is a list"},
    {"x_is_string.ply", PLY_ASCII "element vertex 1\nproperty string x\nproperty float y\nproperty float z\n"
                        "end_header\n1 2 3\n", 0, "unknown property type 'string'"},
    {"id_fraction.ply", PLY_ASCII "element vertex 1\n" PLY_XYZ "property float id\nend_header\n1 2 3 1.5\n", 0,
     "id = 1.5 is not an integer"},
    {"element_without_properties.ply", PLY_ASCII "element vertex 1\nend_header\n\n", 0,
     "element 'vertex' has no properties"},

    /* ---- legacy VTK ---- */
    {"empty.vtk", "", 0, "empty file"},
    {"version_only.vtk", "# vtk DataFile Version 3.0\n", 0, "header ends before the ASCII/BINARY line"},
    {"encoding_cut.vtk", "# vtk DataFile Version 3.0\nbroken\nASC", 0, "expected ASCII or BINARY"},
    {"dataset_cut.vtk", "# vtk DataFile Version 3.0\nbroken\nASCII\nDATASET POLY", 0,
     "DATASET POLY is not supported"},
    {"points_2_62_ascii.vtk", VTK_ASCII "POINTS 4611686018427387904 float\n1 2 3\n", 0,
     "expected 13835058055282163712 values, found 3"},
    {"points_2_62_binary.vtk", BIN(VTK_BINARY "POINTS 4611686018427387904 float\n" ONE_BE_PARTICLE "\n"),
     "13835058055282163712 values of 4 bytes run past the end of the data"},
    {"points_overflow.vtk", VTK_ASCII "POINTS 9223372036854775807 double\n1 2 3\n", 0,
     "value count 9223372036854775807 x 3 overflows"},
    {"points_u64_max.vtk", VTK_ASCII "POINTS 18446744073709551615 float\n1 2 3\n", 0,
     "value count 18446744073709551615 x 3 overflows"},
    {"points_2_64.vtk", VTK_ASCII "POINTS 18446744073709551616 float\n1 2 3\n", 0,
     "point count '18446744073709551616' is not a non-negative integer"},
    {"points_beyond_data_ascii.vtk", VTK_ASCII "POINTS 4 float\n1 2 3 4 5 6 7 8 9\n", 0,
     "expected 12 values, found 9"},
    {"points_beyond_data_binary.vtk", BIN(VTK_BINARY "POINTS 2 float\n" ONE_BE_PARTICLE "\n"),
     "6 values of 4 bytes run past the end of the data"},
    {"field_tuples_2_62.vtk",
     VTK_ASCII "POINTS 1 float\n1 2 3\nPOINT_DATA 1\nFIELD f 1\nrho 1 4611686018427387904 float\n5\n", 0,
     "array 'rho' has 4611686018427387904 tuples for 1 points"},
    {"field_components_overflow.vtk",
     VTK_ASCII "POINTS 1 float\n1 2 3\nPOINT_DATA 1\nFIELD f 1\nextra 4611686018427387904 8 float\n5\n", 0,
     "value count"},
    {"field_arrays_2_62.vtk", VTK_ASCII "POINTS 1 float\n1 2 3\nPOINT_DATA 1\nFIELD f 4611686018427387904\n"
                                        "rho 1 1 float\n5\n", 0, "FIELD ends before all its arrays"},
    {"vertices_2_62.vtk", VTK_ASCII "POINTS 1 float\n1 2 3\nVERTICES 4611686018427387904 4611686018427387904\n1 0\n",
     0, "expected 4611686018427387904 values, found 2"},
    {"lookup_table_overflow.vtk",
     VTK_ASCII "POINTS 1 float\n1 2 3\nPOINT_DATA 1\nLOOKUP_TABLE t 4611686018427387904\n0 0 0 1\n", 0,
     "value count 4611686018427387904 x 4 overflows"},
    {"scalars_components_2_62.vtk",
     VTK_ASCII "POINTS 1 float\n1 2 3\nPOINT_DATA 1\nSCALARS extra float 4611686018427387904\nLOOKUP_TABLE default\n5\n",
     0, "expected 4611686018427387904 values, found 1"},
    {"garbage_number.vtk", VTK_ASCII "POINTS 1 float\n1 2 3e\n", 0, "'3e' is not a number"},
    {"garbage_bytes.vtk", BIN(VTK_ASCII "POINTS 1 float\n1 \x80\x81 3\n"), "'?\?' is not a number"},
    {"points_type_string.vtk", VTK_ASCII "POINTS 1 string\n1 2 3\n", 0, "unsupported data type 'string'"},
    {"scalars_type_bit.vtk", VTK_ASCII "POINTS 1 float\n1 2 3\nPOINT_DATA 1\nSCALARS density bit\n1\n", 0,
     "unsupported data type 'bit'"},
    {"id_negative.vtk",
     VTK_ASCII "POINTS 1 float\n1 2 3\nPOINT_DATA 1\nSCALARS id int 1\nLOOKUP_TABLE default\n-5\n", 0,
     "id = -5 is not an integer"},

    /* ---- CSV ---- */
    {"empty.csv", "", 0, "empty file"},
    {"bom_only.csv", "\xEF\xBB\xBF", 0, "no header line"},
    {"header_cut.csv", "x,y", 0, "x, y and z are required"},
    {"header_only.csv", "x,y,z", 0, "no particles"},
    {"duplicate_column.csv", "x,X,y,z\n1,2,3,4\n", 0, "column 'X' gives x a second time"},
    {"fewer_values.csv", "x,y,z\n1,2,3\n4,5\n", 0, "line 3: expected 3 values, found 2"},
    {"garbage_number.csv", "x,y,z\n1,2,3\n4,5,six\n", 0, "line 3: column 3 (z): 'six' is not a number"},
    {"double_dot.csv", "x,y,z\n1..5,2,3\n", 0, "'1..5' is not a number"},
    {"trailing_junk.csv", "x,y,z\n1,2,3.5abc\n", 0, "'3.5abc' is not a number"},
    {"nul_in_number.csv", BIN("x,y,z\n1,2,3\0\n"), "is not a number"},
    {"garbage_bytes.csv", BIN("x,y,z\n\x01\x02,2,3\n"), "'?\?' is not a number"},
    {"double_overflow.csv", "x,y,z\n1,2,1e999\n", 0, "particle 0: z"},
    {"float_overflow.csv", "x,y,z\n1,3.5e38,2\n", 0, "particle 0: y"},
    {"id_2_32.csv", "x,y,z,id\n1,2,3,4294967296\n", 0, "id = 4.29497e+09 is not an integer"},
    {"id_fraction.csv", "x,y,z,id\n1,2,3,0.5\n", 0, "id = 0.5 is not an integer"},

    /* ---- Houdini classic BGEO (big-endian ints: version nPoints nPrims nPointGroups nPrimGroups
     *      nPointAttrib nVertexAttrib nPrimAttrib nAttrib) ---- */
    {"empty.bgeo", "", 0, "empty file"},
    {"magic_cut.bgeo", "Bge", 0, "not a classic BGEO file"},
    {"json.bgeo", BIN("\x7fNSJb[\x00"), "binary JSON BGEO (Houdini 12 and later) is not supported"},
    {"header_cut.bgeo", BIN("BgeoV" "\0\0\0\x05" "\0\0\0\x01" "\0\0"), "header ends before nPrims"},
    {"points_2_31.bgeo", BIN("BgeoV" "\0\0\0\x05" "\x7f\xff\xff\xff" BGEO_ZEROS(6) "\0\0\0\0" ONE_BE_PARTICLE "\x3f\x80\0\0"),
     "2147483647 points of 16 bytes cannot fit in the 16 bytes left"},
    {"points_negative.bgeo", BIN("BgeoV" "\0\0\0\x05" "\xff\xff\xff\xff" BGEO_ZEROS(6)), "nPoints is negative (-1)"},
    {"attributes_2_31.bgeo", BIN("BgeoV" "\0\0\0\x05" "\0\0\0\x01" BGEO_ZEROS(3) "\x7f\xff\xff\xff" BGEO_ZEROS(3)),
     "2147483647 point attributes (at most 256)"},
    {"attribute_name_cut.bgeo", BIN("BgeoV" "\0\0\0\x05" "\0\0\0\x01" BGEO_ZEROS(3) "\0\0\0\x01" BGEO_ZEROS(3) "\xff\xffv"),
     "point attribute name runs past the end of the data"},
    {"index_strings_2_31.bgeo",
     BIN("BgeoV" "\0\0\0\x05" "\0\0\0\x01" BGEO_ZEROS(3) "\0\0\0\x01" BGEO_ZEROS(3) "\0\x01p" "\0\x01" "\0\0\0\x04"
         "\x7f\xff\xff\xff" "\0\x01" "a"),
     "point attribute 'p': index string 1 runs past the end of the data"},
    {"gzip_cut.bgeo", BIN("\x1f\x8b\x08\x00\x00\x00\x00\x00\x00\x03"), "gzip: compressed stream is truncated"},
    {"gzip_bad_block.bgeo", BIN("\x1f\x8b\x08\x00\x00\x00\x00\x00\x00\x03\x07\x00"), "gzip: corrupt compressed data"},

    /* ---- numpy .npy ---- */
    {"empty.npy", "", 0, "empty file"},
    {"magic_cut.npy", "\x93NUM", 0, "not a numpy .npy file"},
    {"header_len_cut.npy", BIN("\x93NUMPY\x01\x00\x40"), "file ends in the header length"},
    {"header_len_65535.npy", BIN("\x93NUMPY\x01\x00\xff\xff{'descr': '<f4'}"), "header of 65535 bytes runs past"},
    {"rows_2_62.npy", BIN("\x93NUMPY\x01\x00\x46\x00{'descr':'<f4','fortran_order':False,'shape':(4611686018427387904,3)}\n"
                          ONE_LE_PARTICLE),
     "4611686018427387904 x 3 values of 4 bytes cannot fit in the 12 bytes left"},
    {"rows_2_64.npy", BIN("\x93NUMPY\x01\x00\x46\x00{'descr':'<f4','fortran_order':False,'shape':(18446744073709551616,3)}"
                          ONE_LE_PARTICLE),
     "'shape' holds something other than non-negative integers"},
    {"dtype_object.npy", BIN("\x93NUMPY\x01\x00\x32\x00{'descr':'|O','fortran_order':False,'shape':(1,3)}"
                             ONE_LE_PARTICLE),
     "dtype '|O' is not supported"},

    /* ---- VTK XML ---- */
    {"empty.vtu", "", 0, "empty file"},
    {"not_xml.vtu", "\x01\x02\x03", 0, "XML: "},
    {"cut_in_tag.vtu", "<VTKFile type=\"UnstructuredGrid\"><UnstructuredGrid><Piece NumberOfPo", 0, "XML: "},
    {"points_2_62.vtu", VTU_HEAD "<Piece NumberOfPoints=\"4611686018427387904\">" VTU_POINTS("ascii") "1 2 3" VTU_TAIL, 0,
     "NumberOfPoints 4611686018427387904 x 3 components cannot fit"},
    {"points_2_64.vtu", VTU_HEAD "<Piece NumberOfPoints=\"18446744073709551616\">" VTU_POINTS("ascii") "1 2 3" VTU_TAIL, 0,
     "Piece lacks a non-negative integer NumberOfPoints"},
    {"components_2_64.vtu", VTU_HEAD "<Piece NumberOfPoints=\"1\"><Points><DataArray type=\"Float32\" "
                            "NumberOfComponents=\"99999999999999999999\" format=\"ascii\">1 2 3" VTU_TAIL, 0,
     "NumberOfComponents '99999999999999999999' is not a count"},
    {"header_u32_max.vtu", VTU_HEAD "<Piece NumberOfPoints=\"1\">" VTU_POINTS("binary") "/////wAAgD8AAABAAABAQA==" VTU_TAIL, 0,
     "header says 4294967295 bytes, the array holds 12"},
    {"blocks_u32_max.vtu", VTU_ZLIB_HEAD "<Piece NumberOfPoints=\"1\">" VTU_POINTS("binary") "/////wCAAAAMAAAA" VTU_TAIL, 0,
     "4294967295 compressed blocks cannot fit in the data left"},
    {"nested_deep.vtu", VTU_HEAD "<Piece NumberOfPoints=\"1\">" NEST16 NEST16 NEST16 NEST16 "<a>", 0,
     "elements nested more than 64 deep"},
    {"raw_offset_u64_max.vtu", VTU_HEAD "<Piece NumberOfPoints=\"1\"><Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" "
                               "format=\"appended\" offset=\"18446744073709551615\"/></Points></Piece></UnstructuredGrid>"
                               "<AppendedData encoding=\"raw\">_0123456789abcdef", 0,
     "offset 18446744073709551615 is past the appended data's 16 bytes"},
    /* From memory a collection is refused as such, from disk for listing no dataset. */
    {"collection.pvd", "<VTKFile type=\"Collection\"><Collection></Collection></VTKFile>", 0, "collection"},

    /* ---- HDF5 (libhdf5 over the bytes; the signature decides, and a damaged superblock is its reason) ---- */
    {"nosig.h5", "not hdf5 at all", 0, "not an HDF5 file (no \\x89HDF signature)"},
    {"signature_only.h5", BIN("\x89HDF\r\n\x1a\n"), "not a readable HDF5 file"},
    {"superblock_garbage.h5", BIN("\x89HDF\r\n\x1a\n\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff"
                                  "\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff"),
     "not a readable HDF5 file"},
    {"superblock_v0_huge_addresses.h5",
     BIN("\x89HDF\r\n\x1a\n\x00\x00\x00\x00\x00\x08\x08\x00\x04\x00\x10\x00\x00\x00\x00\x00"
         "\x00\x00\x00\x00\x00\x00\x00\x00\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\x7f"
         "\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\xff\x7f"),
     "not a readable HDF5 file"},

    /* ---- raw float32 ---- */
    {"empty.f32", "", 0, "empty file"},
    {"one_byte.f32", "\x01", 0, "1 bytes is not a multiple of 12"},
    {"eleven_bytes.f32", BIN("\x00\x00\x80\x3f" "\x00\x00\x80\x3f" "\x00\x00\x80"), "11 bytes is not a multiple of 12"},
    {"thirteen_bytes.f32", BIN(ONE_LE_PARTICLE "\x00"), "13 bytes is not a multiple of 12"},
    {"nan.f32", BIN("\x00\x00\x80\x3f" "\x00\x00\xc0\x7f" "\x00\x00\x80\x3f"), "particle 0: y = nan"},
    {"minus_inf.f32", BIN(ONE_LE_PARTICLE "\x00\x00\x80\x3f" "\x00\x00\x80\x3f" "\x00\x00\x80\xff"),
     "particle 1: z = -inf"},
};

static int frame_is_empty(const fc_frame *f)
{
    return f->count == 0 && !f->positions && !f->density && !f->velocity && !f->ids;
}

/* The refusal every reader owes a broken file: PARSE, "<label>: ..." naming the reason, no frame. */
static void check_refusal(const broken_file *f, fc_code code, const fc_error *err, const fc_frame *frame,
                          const char *label)
{
    size_t label_len = strlen(label);
    CHECK_MSG(code == FC_ERR_PARSE, "%s: code %d (%s), expected PARSE", label, (int)code, err->message);
    CHECK_MSG(strncmp(err->message, label, label_len) == 0 && strncmp(err->message + label_len, ": ", 2) == 0,
              "message '%s' does not start with '%s: '", err->message, label);
    CHECK_MSG(strstr(err->message, f->reason) != NULL, "message '%s' lacks '%s'", err->message, f->reason);
    CHECK_MSG(frame_is_empty(frame), "%s: a frame came back", label);
}

static void read_from_memory(const broken_file *f, size_t size)
{
    fc_frame frame;
    fc_error err = {FC_OK, ""};
    fc_code code = fc_read_particles_mem((const uint8_t *)f->bytes, size, fc_file_format_from_path(f->name), f->name,
                                         &frame, &err);
    check_refusal(f, code, &err, &frame, f->name);
    fc_frame_free(&frame);
}

static void read_from_file(const broken_file *f, size_t size, const char *dir)
{
    char path[256];
    snprintf(path, sizeof path, "%s/%s", dir, f->name);
    FILE *out = fopen(path, "wb");
    CHECK_MSG(out && (size == 0 || fwrite(f->bytes, 1, size, out) == size) && fclose(out) == 0, "cannot write %s",
              path);
    fc_frame frame;
    fc_error err = {FC_OK, ""};
    fc_code code = fc_read_particles(path, &frame, &err);
    check_refusal(f, code, &err, &frame, path);
    fc_frame_free(&frame);
    unlink(path);
}

int main(void)
{
    char dir[] = "/tmp/fc_hardening_readers_XXXXXX";
    if (!mkdtemp(dir)) {
        perror("mkdtemp");
        return 2;
    }
    for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
        const broken_file *f = &files[i];
        size_t size = f->size ? f->size : strlen(f->bytes);
        int failures_before = test_failures_;
        read_from_memory(f, size);
        read_from_file(f, size, dir);
        if (test_failures_ != failures_before)
            fprintf(stderr, "broken file '%s' not refused as expected\n", f->name);
    }
    rmdir(dir);
    return test_result();
}
