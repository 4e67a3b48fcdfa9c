/* test_hardening_camera_path.c — hostile camera keyframe files for `fluidcast
 * render --camera-path` (client/cli/camera_path.c): nesting far deeper than
 * cJSON's limit, NUL bytes and invalid UTF-8, numbers out of every range, one
 * keyframe too many, a file over the size limit, every truncation and every
 * single-byte corruption of a good file. Each is refused with FC_ERR_PARSE or
 * FC_ERR_LIMIT and a message naming the file, and leaves no keyframe; under
 * the sanitizer build any out-of-bounds access or leak fails. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "camera_path.h"
#include "fc_error.h"
#include "test_util.h"

#define BIN(literal) literal, sizeof literal - 1

static const char GOOD[] = "{ \"keyframes\": [\n"
                           "  { \"frame\": 0, \"eye\": [0, -3, 0], \"target\": [0, 0, 0], \"up\": [0, 0, 1], \"fov\": 40 },\n"
                           "  { \"frame\": 24, \"eye\": [3, 0, 1], \"target\": [0, 0, 0.5], \"fov\": 35 }\n"
                           "] }";

static fc_code parse(const char *bytes, size_t size, fc_camera_path *p, fc_error *err)
{
    err->code = FC_OK;
    err->message[0] = '\0';
    return fc_camera_path_parse(bytes, size, "hostile.json", p, err);
}

static void expect_refused(const char *what, const char *bytes, size_t size, fc_code code, const char *reason)
{
    fc_camera_path p;
    fc_error err;
    fc_code got = parse(bytes, size, &p, &err);
    CHECK_MSG(got == code && err.code == code && strncmp(err.message, "hostile.json", 12) == 0 &&
                  (!reason || strstr(err.message, reason)),
              "%s: code %d \"%s\", expected %d \"%s\"", what, got, err.message, code, reason ? reason : "");
    CHECK_MSG(p.keys == NULL && p.count == 0, "%s left %u keyframes", what, (unsigned)p.count);
    fc_camera_path_free(&p);
}

static char *repeated(const char *head, const char *unit, size_t times, const char *tail, size_t *size)
{
    size_t h = strlen(head), u = strlen(unit), t = strlen(tail);
    char *text = malloc(h + u * times + t + 1);
    if (!text)
        return NULL;
    memcpy(text, head, h);
    for (size_t i = 0; i < times; i++)
        memcpy(text + h + i * u, unit, u);
    memcpy(text + h + u * times, tail, t + 1);
    *size = h + u * times + t;
    return text;
}

static void test_table(void)
{
    expect_refused("NUL inside a member name", BIN("[{\"fr\0me\": 0, \"eye\": [0,-1,0], \"target\": [0,0,0]}]"),
                   FC_ERR_PARSE, NULL);
    expect_refused("NUL after the value", BIN("[{\"frame\": 0, \"eye\": [0,-1,0], \"target\": [0,0,0]}]\0junk"),
                   FC_ERR_PARSE, "not valid JSON");
    expect_refused("invalid UTF-8 member", BIN("[{\"\xff\xfe\": 0}]"), FC_ERR_PARSE, "unknown member");
    expect_refused("frame 1e308", BIN("[{\"frame\": 1e308, \"eye\": [0,-1,0], \"target\": [0,0,0]}]"), FC_ERR_PARSE,
                   "\"frame\" must be a whole number");
    expect_refused("frame NaN spelled out", BIN("[{\"frame\": NaN, \"eye\": [0,-1,0], \"target\": [0,0,0]}]"),
                   FC_ERR_PARSE, "not valid JSON");
    expect_refused("eye -1e400", BIN("[{\"frame\": 0, \"eye\": [0,-1e400,0], \"target\": [0,0,0]}]"), FC_ERR_PARSE,
                   "finite numbers");
    expect_refused("fov -0", BIN("[{\"frame\": 0, \"eye\": [0,-1,0], \"target\": [0,0,0], \"fov\": -0}]"),
                   FC_ERR_PARSE, "\"fov\"");
    expect_refused("eye of 4", BIN("[{\"frame\": 0, \"eye\": [0,-1,0,1], \"target\": [0,0,0]}]"), FC_ERR_PARSE,
                   "array of 3");
    expect_refused("eye nested", BIN("[{\"frame\": 0, \"eye\": [[0],[1],[2]], \"target\": [0,0,0]}]"), FC_ERR_PARSE,
                   "array of 3");
    expect_refused("null keyframe", BIN("[null]"), FC_ERR_PARSE, "not an object");
    size_t size;
    char *deep = repeated("", "[", 100000, "", &size);
    if (deep)
        expect_refused("100000 nested arrays", deep, size, FC_ERR_PARSE, "not valid JSON");
    free(deep);
    char *many = repeated("[", "{\"frame\": 0, \"eye\": [0,-1,0], \"target\": [0,0,0]},", FC_CAMERA_PATH_MAX_KEYS,
                          "{\"frame\": 1, \"eye\": [0,-1,0], \"target\": [0,0,0]}]", &size);
    if (many)
        expect_refused("one keyframe over the limit", many, size, FC_ERR_LIMIT, "at most 100000");
    free(many);
    char *big = repeated("[", " ", FC_CAMERA_PATH_MAX_BYTES, "]", &size);
    if (big)
        expect_refused("a file over the size limit", big, size, FC_ERR_LIMIT, "bytes, at most");
    free(big);
}

/* A prefix of the good file is refused unless only white space was cut. */
static void test_truncations(void)
{
    size_t n = sizeof GOOD - 1;
    for (size_t cut = 0; cut < n; cut++) {
        char *copy = malloc(cut ? cut : 1);   /* exactly the prefix: ASan sees any read past it */
        if (!copy)
            continue;
        memcpy(copy, GOOD, cut);
        fc_camera_path p;
        fc_error err;
        fc_code code = parse(copy, cut, &p, &err);
        CHECK_MSG(code == FC_ERR_PARSE && p.count == 0, "truncated at %zu: code %d", cut, code);
        fc_camera_path_free(&p);
        free(copy);
    }
}

/* Every byte replaced by a few hostile values: accepted or refused cleanly. */
static void test_corruptions(void)
{
    const unsigned char values[] = {0x00, '"', '[', '}', '9', '-', 0xff};
    size_t n = sizeof GOOD - 1, accepted = 0;
    for (size_t at = 0; at < n; at++)
        for (size_t v = 0; v < sizeof values; v++) {
            char *copy = malloc(n);
            if (!copy)
                continue;
            memcpy(copy, GOOD, n);
            copy[at] = (char)values[v];
            fc_camera_path p;
            fc_error err;
            fc_code code = parse(copy, n, &p, &err);
            if (code == FC_OK)
                accepted++;
            else
                CHECK_MSG(code == FC_ERR_PARSE && err.message[0] && p.count == 0, "byte %zu = 0x%02x: code %d %s",
                          at, values[v], code, err.message);
            fc_camera_path_free(&p);
            free(copy);
        }
    printf("%zu single-byte corruptions, %zu still valid keyframe files\n", n * sizeof values, accepted);
}

int main(void)
{
    test_table();
    test_truncations();
    test_corruptions();
    return test_result();
}
