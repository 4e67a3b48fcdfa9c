/* test_camera_path.c — the camera keyframe file of `fluidcast render
 * --camera-path` (client/cli/camera_path.c): both accepted forms, optional
 * up and fov, and the curve: two keyframes move the eye along a straight line
 * at constant speed; three pass through every keyframe, leave it with the
 * Catmull-Rom slope (neighbours' chord over their frame distance) and hold
 * still outside; up and fov linear. Every malformed file is refused with
 * FC_ERR_PARSE naming the line and column, or the keyframe and member; values
 * are checked as the floats the camera carries (a fov of 179.99999999995 is
 * 180.0f, refused). */
#define _POSIX_C_SOURCE 200809L   /* mkstemp, fdopen */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "camera_path.h"
#include "fc_error.h"
#include "fc_frame.h"
#include "test_util.h"

static const fc_camera BASE = {
    .eye = {9, 9, 9}, .target = {0, 0, 0}, .up = {0, 0, 1}, .fov_y_deg = 40, .width = 64, .height = 48};

static fc_code parse(const char *text, fc_camera_path *p, fc_error *err)
{
    return fc_camera_path_parse(text, strlen(text), "cam.json", p, err);
}

static void check_vec(const float got[3], double x, double y, double z, double tol, const char *what)
{
    CHECK_MSG(fabs(got[0] - x) <= tol && fabs(got[1] - y) <= tol && fabs(got[2] - z) <= tol,
              "%s: (%g, %g, %g), expected (%g, %g, %g)", what, got[0], got[1], got[2], x, y, z);
}

static void test_two_keys_are_linear(void)
{
    fc_camera_path p;
    fc_error err;
    const char *text = "{ \"keyframes\": [\n"
                       "  { \"frame\": 10, \"eye\": [0, -2, 1], \"target\": [0, 0, 0], \"fov\": 30 },\n"
                       "  { \"frame\": 20, \"eye\": [4, -6, 1], \"target\": [1, 0, 0], \"up\": [0, 1, 0], "
                       "\"fov\": 50 }\n] }";
    CHECK_CODE(parse(text, &p, &err), FC_OK);
    if (p.count != 2)
        return;
    fc_camera c;
    for (uint32_t f = 10; f <= 20; f++) {
        double s = (f - 10) / 10.0;
        fc_camera_path_at(&p, f, &BASE, &c);
        check_vec(c.eye, 4 * s, -2 - 4 * s, 1, 1e-5, "eye");
        check_vec(c.target, s, 0, 0, 1e-6, "target");
        check_vec(c.up, 0, s, 1 - s, 1e-6, "up (the base's at the first keyframe)");
        CHECK_NEAR(c.fov_y_deg, 30 + 20 * s, 1e-4);
        CHECK(c.width == 64 && c.height == 48);
    }
    fc_camera_path_at(&p, 0, &BASE, &c);   /* before the first: held */
    check_vec(c.eye, 0, -2, 1, 0, "eye before the first keyframe");
    fc_camera_path_at(&p, 4000000000u, &BASE, &c);   /* after the last: held */
    check_vec(c.eye, 4, -6, 1, 0, "eye after the last keyframe");
    CHECK_NEAR(c.fov_y_deg, 50, 0);
    fc_camera_path_free(&p);
}

/* Eye x at frames 0, 4, 12: 0, 4, 0. Tangents (per frame): 1 at 0 (chord to
 * its neighbour), (0 - 0) / 12 = 0 at 4, -0.5 at 12. On [0, 4] with h = 4:
 * x(s) = h10*4*1 + h01*4 + h11*4*0; at frame 2 (s = 0.5): 4*0.125 + 4*0.5 = 2.5. */
static void test_three_keys_catmull_rom(void)
{
    fc_camera_path p;
    fc_error err;
    const char *text = "[ { \"frame\": 0, \"eye\": [0, -1, 0], \"target\": [0, 0, 0] },"
                       "  { \"frame\": 4, \"eye\": [4, -1, 0], \"target\": [0, 0, 0] },"
                       "  { \"frame\": 12, \"eye\": [0, -1, 0], \"target\": [0, 0, 0] } ]";
    CHECK_CODE(parse(text, &p, &err), FC_OK);
    if (p.count != 3)
        return;
    fc_camera c;
    fc_camera_path_at(&p, 4, &BASE, &c);
    check_vec(c.eye, 4, -1, 0, 1e-6, "through the middle keyframe");
    fc_camera_path_at(&p, 2, &BASE, &c);
    check_vec(c.eye, 2.5, -1, 0, 1e-5, "halfway to the middle keyframe");
    /* On [4, 12], h = 8, m0 = 0, m1 = -0.5: at s = 0.5, 4*0.5 + 0.5*0 + 8*(-0.125)*(-0.5) = 2.5. */
    fc_camera_path_at(&p, 8, &BASE, &c);
    check_vec(c.eye, 2.5, -1, 0, 1e-5, "halfway after the middle keyframe");
    CHECK_NEAR(c.fov_y_deg, 40, 0);   /* no fov: --fov's */
    check_vec(c.up, 0, 0, 1, 0, "no up: the sequence's");
    fc_camera_path_free(&p);
}

static void expect_error(const char *text, fc_code code, const char *message)
{
    fc_camera_path p;
    fc_error err = {FC_OK, ""};
    fc_code got = parse(text, &p, &err);
    CHECK_MSG(got == code && strstr(err.message, message), "%s\n-> %d \"%s\", expected %d \"%s\"", text, got,
              err.message, code, message);
    CHECK(p.keys == NULL && p.count == 0);
}

/* Every value is checked as the float the camera carries, not as the file's
 * double: found by fuzz_camera_path, whose regression seed
 * regress_fov_rounds_to_180_as_float.json is the first case. */
static void expect_float_checks(void)
{
    expect_error("[{\"frame\": 0, \"eye\": [0,-1,0], \"target\": [0,0,0], \"fov\": 179.99999999995}]",
                 FC_ERR_PARSE, "cam.json: keyframe 1: \"fov\" must be a number of degrees in (0, 180)");
    expect_error("[{\"frame\": 0, \"eye\": [0,-1,0], \"target\": [0,0,0], \"fov\": 1e-50}]", FC_ERR_PARSE,
                 "cam.json: keyframe 1: \"fov\" must be a number of degrees in (0, 180)");
    expect_error("[{\"frame\": 0, \"eye\": [0,-1,1e39], \"target\": [0,0,0]}]", FC_ERR_PARSE,
                 "cam.json: keyframe 1: \"eye\" must be an array of 3 finite numbers");
    expect_error("[{\"frame\": 0, \"eye\": [0,-1,0], \"target\": [0,0,0], \"up\": [0,-3.5e38,1]}]", FC_ERR_PARSE,
                 "cam.json: keyframe 1: \"up\" must be an array of 3 finite numbers");
    expect_error("[{\"frame\": 0, \"eye\": [1,2,3], \"target\": [1.00000001,2,3]}]", FC_ERR_PARSE,
                 "cam.json: keyframe 1: \"eye\" is the target");
}

/* The largest float below 180 is a valid fov, and the camera at its keyframe
 * is one the daemon accepts. */
static void test_largest_fov(void)
{
    fc_camera_path p;
    fc_error err;
    CHECK_CODE(parse("[{\"frame\": 0, \"eye\": [0,-1,0], \"target\": [0,0,0], \"fov\": 179.99998}]", &p, &err),
               FC_OK);
    if (p.count != 1)
        return;
    fc_camera c;
    fc_camera_path_at(&p, 0, &BASE, &c);
    CHECK_MSG(c.fov_y_deg < 180.0f && c.fov_y_deg > 179.9999f, "fov %.9g", (double)c.fov_y_deg);
    CHECK_CODE(fc_camera_validate(&c, &err), FC_OK);
    fc_camera_path_free(&p);
}

static void test_errors(void)
{
    const char *key0 = "{\"frame\": 0, \"eye\": [0,-1,0], \"target\": [0,0,0]}";
    char text[512];
    expect_error("[\n  {\"frame\": 0,\n   \"eye\": [0, -1 0]}\n]", FC_ERR_PARSE, "cam.json:3:18: not valid JSON (at '0')");
    expect_error("[{\"frame\": 0", FC_ERR_PARSE, "cam.json:1:12: not valid JSON");
    expect_error("", FC_ERR_PARSE, "cam.json:1:1: not valid JSON: the text ends too early");
    snprintf(text, sizeof text, "[%s] x", key0);
    expect_error(text, FC_ERR_PARSE, "cam.json:1:");
    expect_error("{\"frames\": []}", FC_ERR_PARSE, "an object with a \"keyframes\" array");
    expect_error("42", FC_ERR_PARSE, "expected an array of keyframes");
    expect_error("[]", FC_ERR_PARSE, "no keyframe");
    expect_error("[7]", FC_ERR_PARSE, "keyframe 1 is not an object");
    snprintf(text, sizeof text, "[%s, {\"frame\": 5, \"target\": [0,0,0]}]", key0);
    expect_error(text, FC_ERR_PARSE, "keyframe 2: \"eye\" is missing");
    expect_error("[{\"eye\": [0,-1,0], \"target\": [0,0,0]}]", FC_ERR_PARSE, "keyframe 1: \"frame\" is missing");
    expect_error("[{\"frame\": 0, \"eye\": [0,-1,0]}]", FC_ERR_PARSE, "\"target\" is missing");
    expect_error("[{\"frame\": 0, \"eye\": [0,-1], \"target\": [0,0,0]}]", FC_ERR_PARSE,
                 "\"eye\" must be an array of 3 finite numbers");
    expect_error("[{\"frame\": 0, \"eye\": [0,-1,\"2\"], \"target\": [0,0,0]}]", FC_ERR_PARSE,
                 "\"eye\" must be an array of 3");
    expect_error("[{\"frame\": 0, \"eye\": [0,-1,1e999], \"target\": [0,0,0]}]", FC_ERR_PARSE,
                 "\"eye\" must be an array of 3 finite numbers");
    expect_error("[{\"frame\": 1.5, \"eye\": [0,-1,0], \"target\": [0,0,0]}]", FC_ERR_PARSE,
                 "\"frame\" must be a whole number");
    expect_error("[{\"frame\": -1, \"eye\": [0,-1,0], \"target\": [0,0,0]}]", FC_ERR_PARSE,
                 "\"frame\" must be a whole number");
    expect_error("[{\"frame\": 4294967296, \"eye\": [0,-1,0], \"target\": [0,0,0]}]", FC_ERR_PARSE,
                 "\"frame\" must be a whole number");
    expect_error("[{\"frame\": 0, \"eye\": [0,-1,0], \"target\": [0,0,0], \"fov\": 180}]", FC_ERR_PARSE,
                 "\"fov\" must be a number of degrees in (0, 180)");
    expect_float_checks();
    expect_error("[{\"frame\": 0, \"eye\": [0,-1,0], \"target\": [0,0,0], \"fvo\": 30}]", FC_ERR_PARSE,
                 "keyframe 1: unknown member \"fvo\"");
    expect_error("[{\"frame\": 0, \"eye\": [0,-1,0], \"eye\": [0,-2,0], \"target\": [0,0,0]}]", FC_ERR_PARSE,
                 "\"eye\" is given twice");
    expect_error("[{\"frame\": 0, \"eye\": [1,2,3], \"target\": [1,2,3]}]", FC_ERR_PARSE, "\"eye\" is the target");
    snprintf(text, sizeof text, "[%s, {\"frame\": 9, \"eye\": [0,-1,0], \"target\": [0,0,0]}, %s]", key0, key0);
    expect_error(text, FC_ERR_PARSE, "keyframe 3 is at frame 0, not after keyframe 2's frame 9: frames must increase");
    snprintf(text, sizeof text, "[%s, %s]", key0, key0);
    expect_error(text, FC_ERR_PARSE, "keyframe 2 is at frame 0, not after keyframe 1's frame 0");
}

static void test_load(void)
{
    fc_camera_path p;
    fc_error err;
    CHECK_CODE(fc_camera_path_load("/nonexistent/cam.json", &p, &err), FC_ERR_IO);
    CHECK_MSG(strstr(err.message, "/nonexistent/cam.json"), "%s", err.message);
    char path[] = "/tmp/fluidcast-camera-path-XXXXXX";
    int fd = mkstemp(path);
    FILE *f = fd >= 0 ? fdopen(fd, "w") : NULL;
    CHECK(f != NULL);
    if (!f)
        return;
    fputs("{\"keyframes\": [{\"frame\": 3, \"eye\": [0,-1,0], \"target\": [0,0,0]}]}\n", f);
    fclose(f);
    CHECK_CODE(fc_camera_path_load(path, &p, &err), FC_OK);
    CHECK(p.count == 1 && p.keys && p.keys[0].frame == 3);
    fc_camera_path_free(&p);
    remove(path);
}

int main(void)
{
    test_two_keys_are_linear();
    test_three_keys_catmull_rom();
    test_errors();
    test_largest_fov();
    test_load();
    return test_result();
}
