/* test_reader_radius.c — per-particle radii from the files that carry them
 * (FRAME attribute bit 3): PLY and CSV "radius" or "pscale" columns, legacy VTK
 * and VTK XML point data arrays named radius or pscale (BGEO's pscale is in
 * test_reader_bgeo.c); a value that is not a usable radius (0, negative, beyond
 * 1e6) refused naming the particle; a second radius array refused; a VTK XML
 * file with every array the reader maps (positions, velocity, density, ids,
 * radius) read whole (the fuzzer found the fifth array written past the
 * reader's table). */
#include "reader_test_support.h"

static const float RADII[3] = { 0.01f, 0.02f, 0.5f };

static void expect_radii(const char *text, fc_file_format format, const char *name)
{
    fc_frame frame;
    fc_error err = { FC_OK, "" };
    fc_code code = fc_read_particles_mem((const uint8_t *)text, strlen(text), format, name, &frame, &err);
    CHECK_MSG(code == FC_OK, "%s: %s", name, err.message);
    if (code != FC_OK)
        return;
    CHECK_MSG(frame.count == 3 && frame.radius && (fc_frame_attributes(&frame) & FC_ATTR_RADIUS), "%s: no radii",
              name);
    for (int i = 0; frame.radius && i < 3; i++)
        CHECK_MSG(frame.radius[i] == RADII[i], "%s: radius[%d] = %g", name, i, (double)frame.radius[i]);
    check_position(&frame, 2, 7, 8, 9);
    fc_frame_free(&frame);
}

static const char PLY[] = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                          "property float z\nproperty float %s\nend_header\n1 2 3 0.01\n4 5 6 0.02\n7 8 9 %s\n";
static const char CSV[] = "x,y,z,%s\n1,2,3,0.01\n4,5,6,0.02\n7,8,9,%s\n";
static const char VTK[] = "# vtk DataFile Version 3.0\nparticles\nASCII\nDATASET POLYDATA\nPOINTS 3 float\n"
                          "1 2 3 4 5 6 7 8 9\nPOINT_DATA 3\nSCALARS %s float 1\nLOOKUP_TABLE default\n"
                          "0.01 0.02 %s\n";
static const char VTU[] = "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"1.0\">"
                          "<UnstructuredGrid><Piece NumberOfPoints=\"3\" NumberOfCells=\"0\"><Points>"
                          "<DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"ascii\">1 2 3 4 5 6 7 8 9"
                          "</DataArray></Points><PointData><DataArray type=\"Float64\" Name=\"%s\" format=\"ascii\">"
                          "0.01 0.02 %s</DataArray></PointData><Cells>"
                          "<DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\"></DataArray>"
                          "<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\"></DataArray>"
                          "<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\"></DataArray>"
                          "</Cells></Piece></UnstructuredGrid></VTKFile>\n";

static const struct {
    const char *layout;
    fc_file_format format;
    const char *name;
} FILES[] = {
    { PLY, FC_FILE_PLY, "r.ply" },
    { CSV, FC_FILE_CSV, "r.csv" },
    { VTK, FC_FILE_VTK, "r.vtk" },
    { VTU, FC_FILE_VTK_XML, "r.vtu" },
};

static void test_radius_columns(void)
{
    const char *names[] = { "radius", "pscale", "Radius" };
    for (size_t f = 0; f < sizeof FILES / sizeof FILES[0]; f++)
        for (size_t n = 0; n < 3; n++) {
            char text[2048];
            snprintf(text, sizeof text, FILES[f].layout, names[n], "0.5");
            expect_radii(text, FILES[f].format, FILES[f].name);
        }
}

/* The last particle's radius out of its domain: refused, the particle named. */
static void test_bad_radii(void)
{
    const char *values[] = { "0", "-0.5", "2e6", "nan" };
    for (size_t f = 0; f < sizeof FILES / sizeof FILES[0]; f++)
        for (size_t v = 0; v < sizeof values / sizeof values[0]; v++) {
            char text[2048];
            snprintf(text, sizeof text, FILES[f].layout, "radius", values[v]);
            bytes b = { NULL, 0, 0 };
            bytes_append(&b, text, strlen(text));
            fc_frame frame;
            fc_error err = { FC_OK, "" };
            fc_code code = fc_read_particles_mem(b.data, b.len, FILES[f].format, FILES[f].name, &frame, &err);
            CHECK_MSG(code == FC_ERR_PARSE, "%s with radius %s: code %d", FILES[f].name, values[v], (int)code);
            CHECK_MSG(strstr(err.message, "particle 2") != NULL, "%s with radius %s: \"%s\"", FILES[f].name,
                      values[v], err.message);
            if (code == FC_OK)
                fc_frame_free(&frame);
            bytes_free(&b);
        }
}

static void test_two_radius_columns(void)
{
    const char *text = "x,y,z,radius,pscale\n1,2,3,0.1,0.1\n";
    expect_text_failure(text, FC_FILE_CSV, "two.csv", "radius");
}

static void test_vtu_with_every_array(void)
{
    static const char text[] =
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\"><PolyData>"
        "<Piece NumberOfPoints=\"3\"><Points><DataArray type=\"Float32\" NumberOfComponents=\"3\" "
        "format=\"ascii\">1 2 3 4 5 6 7 8 9</DataArray></Points><PointData>"
        "<DataArray type=\"Float32\" Name=\"velocity\" NumberOfComponents=\"3\" format=\"ascii\">"
        "0 0 1 0 0 2 0 0 3</DataArray>"
        "<DataArray type=\"Float64\" Name=\"density\" format=\"ascii\">1000 1001 1002</DataArray>"
        "<DataArray type=\"Int64\" Name=\"id\" format=\"ascii\">7 8 9</DataArray>"
        "<DataArray type=\"Float64\" Name=\"pscale\" format=\"ascii\">0.01 0.02 0.5</DataArray>"
        "</PointData></Piece></PolyData></VTKFile>\n";
    expect_radii(text, FC_FILE_VTK_XML, "all.vtp");
    fc_frame frame;
    fc_error err = { FC_OK, "" };
    if (fc_read_particles_mem((const uint8_t *)text, strlen(text), FC_FILE_VTK_XML, "all.vtp", &frame, &err) != FC_OK)
        return;
    CHECK_MSG(fc_frame_attributes(&frame) == (FC_ATTR_DENSITY | FC_ATTR_VELOCITY | FC_ATTR_IDS | FC_ATTR_RADIUS),
              "attributes 0x%x", fc_frame_attributes(&frame));
    CHECK(frame.velocity && frame.velocity[8] == 3.0f);
    CHECK(frame.density && frame.density[2] == 1002.0f);
    CHECK(frame.ids && frame.ids[1] == 8);
    fc_frame_free(&frame);
}

int main(void)
{
    test_radius_columns();
    test_bad_radii();
    test_two_radius_columns();
    test_vtu_with_every_array();
    return test_result();
}
