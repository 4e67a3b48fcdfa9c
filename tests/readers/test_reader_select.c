/* test_reader_select.c — --select in the readers: parsing every operator and the
 * malformed texts, keeping particles by a DualSPHysics CSV column the frame does
 * not carry (Type), by the frame's own attributes (x, id, speed), several
 * selections at once, and the errors (unknown attribute listing the file's, a
 * selection that keeps nothing). */
#include "reader_test_support.h"

static void test_parse(void)
{
    static const struct { const char *text; fc_select_op op; uint32_t count; double first; const char *name; } ok[] = {
        { "Type=3", FC_SELECT_IN, 1, 3, "Type" },          { "Type==1,3", FC_SELECT_IN, 2, 1, "Type" },
        { "tag!=1, 2", FC_SELECT_NOT_IN, 2, 1, "tag" },    { "x<0.5", FC_SELECT_LT, 1, 0.5, "x" },
        { " x <= -1e3", FC_SELECT_LE, 1, -1e3, "x" },      { "density>1000", FC_SELECT_GT, 1, 1000, "density" },
        { "Pos.z>=2", FC_SELECT_GE, 1, 2, "Pos.z" },
    };
    for (size_t i = 0; i < sizeof ok / sizeof ok[0]; i++) {
        fc_select s;
        fc_error err = { FC_OK, "" };
        CHECK_MSG(fc_select_parse(ok[i].text, &s, &err) == FC_OK, "%s: %s", ok[i].text, err.message);
        CHECK_MSG(s.op == ok[i].op && s.value_count == ok[i].count && s.values[0] == ok[i].first &&
                      strcmp(s.attribute, ok[i].name) == 0 && strcmp(s.text, ok[i].text) == 0,
                  "%s: '%s' op %d, %u values", ok[i].text, s.attribute, (int)s.op, s.value_count);
    }
    static const struct { const char *text, *why; } bad[] = {
        { "Type", "no operator" },          { "=3", "expected an attribute name" },
        { "Type=", "expected a number" },   { "Type=3,", "expected a number" },
        { "Type=a", "expected a number" },  { "x<1,2", "one value after <" },
        { "x<1 2", "one value after <" },   { "x=nan", "expected a number" },
        { "Type=1,2,3,4,5,6,7,8,9,10,11,12,13,14,15,16,17", "more than 16 values" },
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        fc_select s;
        fc_error err = { FC_OK, "" };
        CHECK_CODE(fc_select_parse(bad[i].text, &s, &err), FC_ERR_USAGE);
        CHECK_MSG(strstr(err.message, bad[i].why) != NULL && strstr(err.message, bad[i].text) != NULL, "%s: %s",
                  bad[i].text, err.message);
    }
}

/* Six particles: 0..2 boundary (Type 0), 3..5 fluid (Type 3), x = index, speed = index along vx. */
static const char dualsphysics[] =
    "Pos.x [m];Pos.y [m];Pos.z [m];Idp;Vel.x [m/s];Vel.y [m/s];Vel.z [m/s];Rhop [kg/m^3];Type;Mk;\n"
    "m;m;m;-;m/s;m/s;m/s;kg/m^3;-;-;\n"
    "0;0;0;10;0;0;0;1000;0;0;\n"
    "1;0;0;11;1;0;0;1001;0;0;\n"
    "2;0;0;12;2;0;0;1002;0;0;\n"
    "3;0;0;13;3;0;0;1003;3;1;\n"
    "4;0;0;14;4;0;0;1004;3;1;\n"
    "5;0;0;15;5;0;0;1005;3;2;\n";

static fc_code read_selected(const char *const *texts, size_t n, fc_frame *f, fc_error *err)
{
    fc_read_options o = { 0 };
    for (size_t i = 0; i < n; i++)
        CHECK(fc_select_parse(texts[i], &o.select[o.select_count++], err) == FC_OK);
    return fc_read_particles_mem_with((const uint8_t *)dualsphysics, sizeof dualsphysics - 1, FC_FILE_CSV, "d.csv",
                                      &o, f, err);
}

static void expect_kept(const char *const *texts, size_t n, const uint32_t *ids, uint64_t count)
{
    fc_frame f;
    fc_error err = { FC_OK, "" };
    CHECK_MSG(read_selected(texts, n, &f, &err) == FC_OK, "%s: %s", texts[0], err.message);
    CHECK_MSG(f.count == count, "%s: %llu particles", texts[0], (unsigned long long)f.count);
    for (uint64_t i = 0; i < count && i < f.count; i++) {
        uint32_t k = ids[i] - 10;
        CHECK_MSG(f.ids[i] == ids[i] && f.positions[3 * i] == (float)k && f.velocity[3 * i] == (float)k &&
                      f.density[i] == 1000.0f + (float)k,
                  "%s: particle %llu is id %u", texts[0], (unsigned long long)i, f.ids[i]);
    }
    fc_frame_free(&f);
}

static void test_keep(void)
{
    expect_kept((const char *[]){ "Type=3" }, 1, (const uint32_t[]){ 13, 14, 15 }, 3);
    expect_kept((const char *[]){ "type!=3" }, 1, (const uint32_t[]){ 10, 11, 12 }, 3);
    expect_kept((const char *[]){ "Mk=0,2" }, 1, (const uint32_t[]){ 10, 11, 12, 15 }, 4);
    expect_kept((const char *[]){ "x<2" }, 1, (const uint32_t[]){ 10, 11 }, 2);
    expect_kept((const char *[]){ "x<=2" }, 1, (const uint32_t[]){ 10, 11, 12 }, 3);
    expect_kept((const char *[]){ "id>13" }, 1, (const uint32_t[]){ 14, 15 }, 2);
    expect_kept((const char *[]){ "speed>=4" }, 1, (const uint32_t[]){ 14, 15 }, 2);
    expect_kept((const char *[]){ "Type=3", "density<1005", "Mk=1" }, 3, (const uint32_t[]){ 13, 14 }, 2);
    /* Without a selection the other columns cost nothing and nothing changes. */
    fc_frame f;
    fc_error err = { FC_OK, "" };
    CHECK(read_selected(NULL, 0, &f, &err) == FC_OK && f.count == 6);
    fc_frame_free(&f);
}

static void test_errors(void)
{
    fc_frame f;
    fc_error err = { FC_OK, "" };
    CHECK_CODE(read_selected((const char *[]){ "Typ=3" }, 1, &f, &err), FC_ERR_USAGE);
    CHECK_MSG(strcmp(err.message, "d.csv: --select 'Typ=3': no attribute 'Typ' (this file has: x, y, z, density, vx, "
                                  "vy, vz, speed, id, Type, Mk)") == 0, "%s", err.message);
    CHECK(frame_is_empty(&f));
    CHECK_CODE(read_selected((const char *[]){ "Type=3", "x<3" }, 2, &f, &err), FC_ERR_USAGE);
    CHECK_MSG(strcmp(err.message, "d.csv: --select 'x<3' keeps none of the 3 particles") == 0, "%s", err.message);
    CHECK(frame_is_empty(&f));
    /* A file without velocities has no speed to select by. */
    fc_read_options o = { 0 };
    CHECK(fc_select_parse("speed>1", &o.select[o.select_count++], &err) == FC_OK);
    static const char plain[] = "x,y,z\n1,2,3\n";
    CHECK_CODE(fc_read_particles_mem_with((const uint8_t *)plain, sizeof plain - 1, FC_FILE_CSV, "p.csv", &o, &f, &err),
               FC_ERR_USAGE);
    CHECK_MSG(strstr(err.message, "no attribute 'speed' (this file has: x, y, z)") != NULL, "%s", err.message);
}

/* Legacy VTK as DualSPHysics' PartVTK writes it: Type and Mk as one-component point arrays. */
static void test_legacy_vtk(void)
{
    static const char vtk[] = "# vtk DataFile Version 3.0\nparts\nASCII\nDATASET POLYDATA\n"
                              "POINTS 4 double\n0 0 0\n1 0 0\n2 0 0\n3 0 0\n"
                              "POINT_DATA 4\nSCALARS Idp unsigned_int\nLOOKUP_TABLE default\n10 11 12 13\n"
                              "SCALARS Type unsigned_char\nLOOKUP_TABLE default\n0 3 0 3\n"
                              "FIELD FieldData 1\nMk 1 4 unsigned_char\n0 1 0 2\n";
    fc_read_options o = { 0 };
    fc_error err = { FC_OK, "" };
    CHECK(fc_select_parse("Type=3", &o.select[o.select_count++], &err) == FC_OK);
    CHECK(fc_select_parse("Mk>=2", &o.select[o.select_count++], &err) == FC_OK);
    fc_frame f;
    CHECK_MSG(fc_read_particles_mem_with((const uint8_t *)vtk, sizeof vtk - 1, FC_FILE_VTK, "p.vtk", &o, &f, &err) ==
                  FC_OK, "%s", err.message);
    CHECK_MSG(f.count == 1 && f.ids && f.ids[0] == 13 && f.positions[0] == 3.0f, "%llu", (unsigned long long)f.count);
    fc_frame_free(&f);
}

int main(void)
{
    test_parse();
    test_keep();
    test_errors();
    test_legacy_vtk();
    return test_result();
}
