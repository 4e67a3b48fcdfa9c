/* test_reader_csv.c — CSV with a header line: exact values, column names
 * case-insensitive and trimmed, extra columns ignored, comments, blank lines,
 * CRLF and a byte-order mark; DualSPHysics' ';'-separated CSV (units in the
 * names or on a line of their own, a preamble, trailing ';'); and broken files. */
#include "reader_test_support.h"

static const char *GOOD_CSV =
    "\xEF\xBB\xBF# exported by a solver\r\n"
    " X , y,Z ,label, Density,vx,VY , vz,ID\r\n"
    "0.5,-1.25,3,first,1000.5,0.125,-0.25,4,7\r\n"
    "\r\n"
    "  # a comment between rows\r\n"
    "-0.001, 2e3 ,1.5e-2,,998.25,0,0,-9.81,4294967295\r\n"
    "10,20,30,third,1001,1,2,3,0";

static void test_good(void)
{
    fc_frame frame;
    fc_error err = { FC_OK, "" };
    CHECK_MSG(fc_read_particles_mem((const uint8_t *)GOOD_CSV, strlen(GOOD_CSV), FC_FILE_CSV, "g.csv", &frame, &err) ==
                  FC_OK,
              "%s", err.message);
    CHECK(frame.count == 3 && frame.density && frame.velocity && frame.ids);
    if (frame.count == 3 && frame.density && frame.velocity && frame.ids) {
        check_position(&frame, 0, 0.5f, -1.25f, 3.0f);
        check_position(&frame, 1, -0.001f, 2000.0f, 0.015f);
        check_position(&frame, 2, 10.0f, 20.0f, 30.0f);
        check_velocity(&frame, 0, 0.125f, -0.25f, 4.0f);
        check_velocity(&frame, 1, 0.0f, 0.0f, -9.81f);
        check_velocity(&frame, 2, 1.0f, 2.0f, 3.0f);
        CHECK(frame.density[0] == 1000.5f && frame.density[1] == 998.25f && frame.density[2] == 1001.0f);
        CHECK(frame.ids[0] == 7u && frame.ids[1] == 4294967295u && frame.ids[2] == 0u);
    }
    fc_frame_free(&frame);
}

static void test_positions_and_rho(void)
{
    const char *text = "z,rho,y,x\n1,2,3,4\n";
    fc_frame frame;
    fc_error err = { FC_OK, "" };
    CHECK_MSG(fc_read_particles_mem((const uint8_t *)text, strlen(text), FC_FILE_CSV, "r.csv", &frame, &err) == FC_OK,
              "%s", err.message);
    CHECK(frame.count == 1 && frame.density && !frame.velocity && !frame.ids);
    if (frame.count == 1 && frame.density) {
        check_position(&frame, 0, 4.0f, 3.0f, 1.0f);
        CHECK(frame.density[0] == 2.0f);
    }
    fc_frame_free(&frame);
}

static void test_errors(void)
{
    const char *message = expect_text_failure("x,y,z\n1,2,3\n4,5\n", FC_FILE_CSV, "frame.csv", NULL);
    CHECK_MSG(strcmp(message, "frame.csv: line 3: expected 3 values, found 2") == 0, "got '%s'", message);
    expect_text_failure("x,y,z\n1,2,3,4\n", FC_FILE_CSV, "f.csv", "line 2: expected 3 values, found 4");
    expect_text_failure("x,y,density\n1,2,3\n", FC_FILE_CSV, "f.csv", "line 1: header: x, y and z are required");
    expect_text_failure("x,y,z,vx,vz\n1,2,3,4,5\n", FC_FILE_CSV, "f.csv", "velocity needs all of vx, vy and vz");
    expect_text_failure("x,y,z,rho,density\n1,2,3,4,5\n", FC_FILE_CSV, "f.csv",
                        "line 1: column 'density' gives density a second time");
    expect_text_failure("x,y,z\n1,2,3\n1,two,3\n", FC_FILE_CSV, "f.csv", "line 3: column 2 (y): 'two' is not a number");
    expect_text_failure("x,y,z\n1,,3\n", FC_FILE_CSV, "f.csv", "column 2 (y): '' is not a number");
    expect_text_failure("x,y,z\n1,2,3\n1,2,inf\n", FC_FILE_CSV, "f.csv", "line 3: particle 1: z = inf");
    expect_text_failure("x,y,z\n1,2,NaN\n", FC_FILE_CSV, "f.csv", "particle 0: z = nan");
    expect_text_failure("x,y,z,id\n1,2,3,-1\n", FC_FILE_CSV, "f.csv", "id = -1 is not an integer");
    expect_text_failure("x,y,z\n# nothing\n\n", FC_FILE_CSV, "f.csv", "no particles");
    expect_text_failure("# only a comment\n", FC_FILE_CSV, "f.csv", "no header line");
    expect_text_failure("x;y\n1;2\n", FC_FILE_CSV, "f.csv", "x, y and z are required");
    expect_text_failure("Pos.x [m];Pos.y [m];Pos.z [m];\n1;2;3;4;\n", FC_FILE_CSV, "f.csv",
                        "line 2: expected 3 values, found 4");
    expect_text_failure("Pos.x [m];Pos.y [m];Pos.z [m];Vel.x [m/s];Vel.z [m/s];\n1;2;3;4;5;\n", FC_FILE_CSV, "f.csv",
                        "velocity needs all of vx, vy and vz");
    expect_text_failure("Pos.x [m];Pos.y [m];Pos.z [m];Idp;\n1;2;3;-4;\n", FC_FILE_CSV, "f.csv",
                        "id = -4 is not an integer");
    /* A preamble longer than DualSPHysics writes is not searched for a header. */
    expect_text_failure("a;b\n1;2\n3;4\n5;6\n7;8\n9;10\n11;12\n13;14\n15;16\nx;y;z\n1;2;3\n", FC_FILE_CSV, "f.csv",
                        "line 1: header: x, y and z are required");
}

/* DualSPHysics' PartVTK -savecsv: a line of totals and its values, a blank line, the header with units in
 * brackets, values in exponent notation, every line ending with ';'; Type and Mk ignored. */
static const char *DUALSPHYSICS_CSV =
    "TimeStep [s];Np;Nbound;Nfixed;Nmoving;Nfloat;Nfluid;\n"
    "1.500000E-01;3;1;1;0;0;2;\n"
    "\n"
    "Pos.x [m];Pos.y [m];Pos.z [m];Idp;Vel.x [m/s];Vel.y [m/s];Vel.z [m/s];Rhop [kg/m^3];Type;Mk;\n"
    "5.0000000E-01;-1.2500000E+00;3.0000000E+00;7;1.2500000E-01;-2.5000000E-01;4.0000000E+00;1.0005000E+03;0;1;\n"
    "-1.0000000E-03;2.0000000E+03;1.5000000E-02;4294967295;0.0000000E+00;0.0000000E+00;-9.8100004E+00;9.9825000E+02;3;11;\n"
    "1.0E+01;2.0E+01;3.0E+01;0;1;2;3;1001;3;11;\n";

static void check_three(const char *text, const char *name, bool with_ids)
{
    fc_frame frame;
    fc_error err = { FC_OK, "" };
    CHECK_MSG(fc_read_particles_mem((const uint8_t *)text, strlen(text), FC_FILE_CSV, name, &frame, &err) == FC_OK,
              "%s: %s", name, err.message);
    CHECK(frame.count == 3 && frame.density && frame.velocity && (frame.ids != NULL) == with_ids);
    if (frame.count == 3 && frame.density && frame.velocity) {
        check_position(&frame, 0, 0.5f, -1.25f, 3.0f);
        check_position(&frame, 1, -0.001f, 2000.0f, 0.015f);
        check_velocity(&frame, 1, 0.0f, 0.0f, -9.81f);
        check_velocity(&frame, 2, 1.0f, 2.0f, 3.0f);
        CHECK(frame.density[0] == 1000.5f && frame.density[1] == 998.25f && frame.density[2] == 1001.0f);
        if (with_ids && frame.ids)
            CHECK(frame.ids[0] == 7u && frame.ids[1] == 4294967295u && frame.ids[2] == 0u);
    }
    fc_frame_free(&frame);
}

static void test_dualsphysics(void)
{
    check_three(DUALSPHYSICS_CSV, "PartFluid_0003.csv", true);
    /* Names and units on lines of their own, CRLF, no trailing ';'. */
    check_three("Pos.x;Pos.y;Pos.z;Vel.x;Vel.y;Vel.z;Rhop\r\n"
                "m;m;m;m/s;m/s;m/s;kg/m^3\r\n"
                "0.5;-1.25;3;0.125;-0.25;4;1000.5\r\n"
                "-0.001;2000;0.015;0;0;-9.81;998.25\r\n"
                "10;20;30;1;2;3;1001\r\n",
                "units.csv", false);
    bytes b = { NULL, 0, 0 };
    bytes_append(&b, DUALSPHYSICS_CSV, strlen(DUALSPHYSICS_CSV));
    const char *first_row_end = strstr(DUALSPHYSICS_CSV, ";0;1;\n") + 4;
    check_truncations(&b, FC_FILE_CSV, (size_t)(first_row_end - DUALSPHYSICS_CSV) - 1, 3);
    check_mutations(&b, FC_FILE_CSV, 3000, 31u);
    bytes_free(&b);
}

static void test_truncations_and_mutations(void)
{
    bytes b = { NULL, 0, 0 };
    bytes_append(&b, GOOD_CSV, strlen(GOOD_CSV));
    /* Cutting after a complete row leaves a valid, shorter file: only cuts before
     * the end of the first row must fail. */
    const char *first_row_end = strstr(GOOD_CSV, ",7\r\n") + 2;
    check_truncations(&b, FC_FILE_CSV, (size_t)(first_row_end - GOOD_CSV) - 1, 3);
    check_mutations(&b, FC_FILE_CSV, 3000, 3u);
    bytes_free(&b);
}

int main(void)
{
    test_good();
    test_positions_and_rho();
    test_errors();
    test_dualsphysics();
    test_truncations_and_mutations();
    return test_result();
}
