/* test_flat_constants.c — the text side of flat_constants.h, without GL:
 * which declarations become flat inputs and how they are packed, that the
 * rewritten source keeps every other line and the line count (the driver's
 * messages name the file's lines), what the vertex unit forwards, and the
 * errors: a uniform declared twice differently, a fragment stage with an
 * input of its own. test_constant_paths renders with it. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "flat_constants.h"
#include "test_util.h"

static const char camera_source[] =
    "#version 450 core\n"
    "layout(location = 0) uniform vec2 focal;           // P[0][0], P[1][1]\n"
    "layout(location = 1) uniform mat3 view_to_world;\n"
    "layout(location = 4) uniform vec3 eye_world;\n"
    "vec3 f() { return eye_world; }\n";

static const char shade_source[] =
    "#version 450 core\n"
    "layout(early_fragment_tests) in;\n"
    "layout(binding = 2) uniform sampler2D background;\n"
    "layout(location = 0) uniform vec2 focal;           // again, as in camera\n"
    "layout(location = 9) uniform float fresnel_f0;\n"
    "layout(location = 15) uniform bool use_environment_map;\n"
    "layout(location = 8) uniform vec2 taps[4];\n"
    "layout(location = 42) uniform ivec2 surface_size;\n"
    "layout(location = 12) uniform float particle_radius;\n"
    "layout(location = 0) out vec4 color;\n"
    "void main() { color = vec4(focal, fresnel_f0, particle_radius); }";   /* no newline at the end */

static const fc_flat_constant *find(const fc_flat_constants *c, const char *name)
{
    for (size_t i = 0; i < c->count; i++)
        if (strcmp(c->items[i].name, name) == 0)
            return &c->items[i];
    return NULL;
}

static int lines(const char *text)
{
    int n = 1;
    for (; *text; text++)
        n += *text == '\n';
    return n;
}

static void test_collect_and_pack(fc_flat_constants *c)
{
    fc_error err = {0};
    CHECK_CODE(fc_flat_constants_collect(c, camera_source, "camera", &err), FC_OK);
    CHECK_CODE(fc_flat_constants_collect(c, shade_source, "shade", &err), FC_OK);
    /* focal once; the sampler, the bool and the array stay uniforms. */
    CHECK_MSG(c->count == 6, "%zu constants", c->count);
    CHECK(!find(c, "background") && !find(c, "use_environment_map") && !find(c, "taps"));
    fc_flat_constants_assign(c, 32);
    const fc_flat_constant *focal = find(c, "focal"), *m = find(c, "view_to_world"), *eye = find(c, "eye_world"),
                           *f0 = find(c, "fresnel_f0"), *size = find(c, "surface_size"),
                           *r = find(c, "particle_radius");
    CHECK(focal && m && eye && f0 && size && r);
    if (!(focal && m && eye && f0 && size && r))
        return;
    /* In order: focal in a new location, the matrix in three whole ones, the
     * vec3 in a new one, fresnel_f0 after focal, the int vector apart from
     * the floats, particle_radius filling the vec3's location. */
    CHECK(focal->slot == 0 && focal->component == 0);
    CHECK(m->slot == 1 && m->component == -1);
    CHECK(eye->slot == 4 && eye->component == 0);
    CHECK(f0->slot == 0 && f0->component == 2);
    CHECK(size->slot == 5 && size->component == 0);
    CHECK(r->slot == 0 && r->component == 3);
    CHECK_MSG(c->slots_used == 6, "%d locations", c->slots_used);
}

static void test_rewrite(const fc_flat_constants *c)
{
    char *out = NULL;
    fc_error err = {0};
    CHECK_CODE(fc_flat_constants_rewrite(c, shade_source, &out, &err), FC_OK);
    if (!out)
        return;
    CHECK_MSG(lines(out) == lines(shade_source), "%d lines, the source has %d", lines(out), lines(shade_source));
    CHECK(strstr(out, "layout(location = 0, component = 0) flat in vec2 focal;           // again, as in camera\n"));
    CHECK(strstr(out, "layout(location = 0, component = 3) flat in float particle_radius;\n"));
    CHECK(strstr(out, "layout(location = 5, component = 0) flat in ivec2 surface_size;\n"));
    CHECK(strstr(out, "layout(location = 15) uniform bool use_environment_map;\n"));
    CHECK(strstr(out, "layout(location = 8) uniform vec2 taps[4];\n"));
    CHECK(strstr(out, "layout(early_fragment_tests) in;\n"));
    CHECK(strstr(out, "void main() { color = vec4(focal, fresnel_f0, particle_radius); }") &&
          out[strlen(out) - 1] == '}');
    free(out);
    CHECK_CODE(fc_flat_constants_rewrite(c, camera_source, &out, &err), FC_OK);
    CHECK(out && strstr(out, "layout(location = 1) flat in mat3 view_to_world;\n"));
    free(out);
}

static void test_vertex_source(const fc_flat_constants *c)
{
    char *out = NULL;
    fc_error err = {0};
    CHECK_CODE(fc_flat_constants_vertex_source(c, &out, &err), FC_OK);
    if (!out)
        return;
    CHECK(strncmp(out, "#version 450 core\n", 18) == 0);
    CHECK(strstr(out, "layout(location = 1) uniform mat3 view_to_world;\n"
                      "layout(location = 1) flat out mat3 fc_flat_view_to_world;\n"));
    CHECK(strstr(out, "layout(location = 12) uniform float particle_radius;\n"
                      "layout(location = 0, component = 3) flat out float fc_flat_particle_radius;\n"));
    CHECK(strstr(out, "    fc_flat_surface_size = surface_size;\n"));
    CHECK(!strstr(out, "taps") && !strstr(out, "use_environment_map"));
    free(out);
}

/* With room for two locations, the matrix does not fit and stays a uniform. */
static void test_no_room(void)
{
    fc_flat_constants *c = calloc(1, sizeof *c);
    fc_error err = {0};
    if (!c)
        return;
    CHECK_CODE(fc_flat_constants_collect(c, camera_source, "camera", &err), FC_OK);
    fc_flat_constants_assign(c, 2);
    CHECK(find(c, "focal")->slot == 0 && find(c, "view_to_world")->slot == -1 && find(c, "eye_world")->slot == 1);
    char *out = NULL;
    CHECK_CODE(fc_flat_constants_rewrite(c, camera_source, &out, &err), FC_OK);
    CHECK(out && strstr(out, "layout(location = 1) uniform mat3 view_to_world;\n"));
    free(out);
    free(c);
}

static void test_errors(void)
{
    fc_flat_constants *c = calloc(1, sizeof *c);
    fc_error err = {0};
    if (!c)
        return;
    CHECK_CODE(fc_flat_constants_collect(c, camera_source, "camera", &err), FC_OK);
    CHECK_CODE(fc_flat_constants_collect(c, "layout(location = 3) uniform vec2 focal;\n", "other", &err), FC_ERR_GL);
    CHECK_MSG(strstr(err.message, "focal") && strstr(err.message, "other"), "%s", err.message);
    CHECK_CODE(fc_flat_constants_collect(c, "layout(location = 0) uniform vec3 focal;\n", "other", &err), FC_ERR_GL);
    CHECK_CODE(fc_flat_constants_collect(c, "in vec3 view_position;\n", "mesh", &err), FC_ERR_GL);
    CHECK_CODE(fc_flat_constants_collect(c, "layout(location = 2) flat in int id;\n", "mesh", &err), FC_ERR_GL);
    CHECK_MSG(strstr(err.message, "without inputs"), "%s", err.message);
    free(c);
}

int main(void)
{
    fc_flat_constants *c = calloc(1, sizeof *c);
    CHECK(c);
    if (c) {
        test_collect_and_pack(c);
        test_rewrite(c);
        test_vertex_source(c);
    }
    free(c);
    test_no_room();
    test_errors();
    return test_result();
}
