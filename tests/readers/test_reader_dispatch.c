/* test_reader_dispatch.c — format detection from the extension, reading real
 * files of every format, I/O errors and argument checks. */
#include <sys/stat.h>
#include "reader_test_support.h"

static void test_format_from_path(void)
{
    CHECK(fc_file_format_from_path("frame.f32") == FC_FILE_F32);
    CHECK(fc_file_format_from_path("/data/run.1/FRAME.PLY") == FC_FILE_PLY);
    CHECK(fc_file_format_from_path("out/step_0001.vtk") == FC_FILE_VTK);
    CHECK(fc_file_format_from_path("table.Csv") == FC_FILE_CSV);
    CHECK(fc_file_format_from_path("frame.ply.gz") == FC_FILE_UNKNOWN);
    CHECK(fc_file_format_from_path("dir.ply/frame") == FC_FILE_UNKNOWN);
    CHECK(fc_file_format_from_path("frame") == FC_FILE_UNKNOWN);
    CHECK(fc_file_format_from_path("frame.") == FC_FILE_UNKNOWN);
    CHECK(fc_file_format_from_path("frame.plyx") == FC_FILE_UNKNOWN);
    CHECK(fc_file_format_from_path(NULL) == FC_FILE_UNKNOWN);
}

/* Writes size bytes of text as <name> in the temp dir and reads it back through fc_read_particles. */
static fc_code read_temp_file(const char *name, const char *text, size_t size, fc_frame *frame, fc_error *err)
{
    bytes b = { NULL, 0, 0 };
    bytes_append(&b, text, size);
    const char *path = write_temp_file(name, &b);
    bytes_free(&b);
    fc_code code = fc_read_particles(path, frame, err);
    remove_temp_file(name);
    return code;
}

#define TEXT_FILE(name, text) { name, text, sizeof(text) - 1 }

static void test_files_of_each_format(void)
{
    static const struct {
        const char *name;
        const char *text;
        size_t size;
    } files[] = {
        TEXT_FILE("a.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                           "property float z\nend_header\n1.5 -2 0.25\n"),
        TEXT_FILE("a.VTK", "# vtk DataFile Version 3.0\nt\nASCII\nDATASET POLYDATA\nPOINTS 1 float\n1.5 -2 0.25\n"),
        TEXT_FILE("a.csv", "x,y,z\n1.5,-2,0.25\n"),
        TEXT_FILE("a.f32", "\x00\x00\xc0\x3f\x00\x00\x00\xc0\x00\x00\x80\x3e"),
    };
    for (size_t i = 0; i < sizeof files / sizeof files[0]; i++) {
        fc_frame frame;
        fc_error err = { FC_OK, "" };
        CHECK_MSG(read_temp_file(files[i].name, files[i].text, files[i].size, &frame, &err) == FC_OK, "%s: %s",
                  files[i].name, err.message);
        CHECK_MSG(frame.count == 1, "%s: %llu particles", files[i].name, (unsigned long long)frame.count);
        if (frame.count == 1)
            check_position(&frame, 0, 1.5f, -2.0f, 0.25f);
        fc_frame_free(&frame);
    }
}

static void test_file_errors(void)
{
    fc_frame frame;
    fc_error err = { FC_OK, "" };
    char path[300];

    /* A broken file's message names the path it was opened with. */
    CHECK_CODE(read_temp_file("broken.csv", "x,y,z\n1,2\n", 10, &frame, &err), FC_ERR_PARSE);
    snprintf(path, sizeof path, "%s/broken.csv: line 2: expected 3 values, found 2", temp_dir());
    CHECK_MSG(strcmp(err.message, path) == 0, "got '%s'", err.message);
    CHECK(frame_is_empty(&frame));

    CHECK_CODE(read_temp_file("empty.ply", "", 0, &frame, &err), FC_ERR_PARSE);
    CHECK(strstr(err.message, "empty.ply: empty file") != NULL);

    snprintf(path, sizeof path, "%s/missing.vtk", temp_dir());
    CHECK_CODE(fc_read_particles(path, &frame, &err), FC_ERR_IO);
    CHECK(strstr(err.message, path) == err.message && strstr(err.message, "cannot open") != NULL);
    CHECK(frame_is_empty(&frame));

    snprintf(path, sizeof path, "%s/folder.ply", temp_dir());
    CHECK(mkdir(path, 0700) == 0);
    CHECK_CODE(fc_read_particles(path, &frame, &err), FC_ERR_IO);
    CHECK(strstr(err.message, "not a regular file") != NULL);
    rmdir(path);

    /* An unknown extension is read first (an HDF5 file may have any name), then refused unless HDF5. */
    bytes text = { NULL, 0, 0 };
    bytes_printf(&text, "1 2 3\n");
    const char *xyz = write_temp_file("particles.xyz", &text);
    CHECK_CODE(fc_read_particles(xyz, &frame, &err), FC_ERR_PARSE);
    CHECK(strstr(err.message, xyz) == err.message && strstr(err.message, ": unknown particle file format") != NULL);
    remove_temp_file("particles.xyz");
    bytes_free(&text);
}

static void test_arguments(void)
{
    fc_frame frame;
    fc_error err = { FC_OK, "" };
    const uint8_t data[12] = { 0 };
    CHECK_CODE(fc_read_particles(NULL, &frame, &err), FC_ERR_USAGE);
    CHECK_CODE(fc_read_particles("a.ply", NULL, &err), FC_ERR_USAGE);
    CHECK_CODE(fc_read_particles_mem(data, sizeof data, FC_FILE_F32, "a", NULL, &err), FC_ERR_USAGE);
    CHECK_CODE(fc_read_particles_mem(NULL, 12, FC_FILE_F32, "a", &frame, &err), FC_ERR_USAGE);
    CHECK_CODE(fc_read_particles_mem(data, sizeof data, FC_FILE_UNKNOWN, "blob", &frame, &err), FC_ERR_PARSE);
    CHECK(strstr(err.message, "blob: unknown particle file format") == err.message);
    CHECK_CODE(fc_read_particles_mem(data, 5, FC_FILE_F32, NULL, &frame, &err), FC_ERR_PARSE);
    CHECK(strstr(err.message, "<memory>: ") == err.message);
    /* A NULL fc_error is allowed: only the code comes back. */
    CHECK_CODE(fc_read_particles_mem(data, 5, FC_FILE_F32, "a", &frame, NULL), FC_ERR_PARSE);
    CHECK_CODE(fc_read_particles_mem(data, sizeof data, FC_FILE_F32, "a", &frame, NULL), FC_OK);
    CHECK(frame.count == 1);
    fc_frame_free(&frame);
}

int main(void)
{
    test_format_from_path();
    test_files_of_each_format();
    test_file_errors();
    test_arguments();
    remove_temp_dir();
    return test_result();
}
