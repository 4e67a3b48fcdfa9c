/* write_test_meshes.c — writes one closed surface mesh (a latitude-longitude
 * sphere, every attribute set from the position) through each of fluidcast
 * mesh's writers (client/cli/mesh_write.h) into DIR, for check_mesh_files.py to
 * read back with VTK's readers; and checks that a bad path or extension is
 * refused with its code and leaves no file. Prints "V T" on success.
 *
 * usage: write_test_meshes DIR */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "mesh_write.h"
#include "test_util.h"

#define RINGS 40u       /* latitude bands */
#define SEGMENTS 60u    /* longitude segments */

static uint32_t ring_vertex(uint32_t ring, uint32_t segment)   /* ring 1..RINGS-1 */
{
    return 1 + (ring - 1) * SEGMENTS + segment % SEGMENTS;
}

static void add_triangle(fc_surface_mesh *m, uint32_t a, uint32_t b, uint32_t c)
{
    uint32_t *t = m->indices + 3ull * m->triangle_count++;
    t[0] = a, t[1] = b, t[2] = c;
}

/* The unit sphere about (1, 2, 3), counter-clockwise seen from outside. */
static fc_surface_mesh sphere(void)
{
    fc_surface_mesh m = {.vertex_count = 2 + (RINGS - 1) * SEGMENTS, .attributes = 15u};
    uint32_t v = m.vertex_count, t = 2 * SEGMENTS * (RINGS - 1);
    m.positions = malloc(12ull * v), m.normals = malloc(12ull * v), m.indices = malloc(12ull * t);
    m.speed = malloc(4ull * v), m.density = malloc(4ull * v), m.velocity = malloc(12ull * v), m.id = malloc(4ull * v);
    for (uint32_t i = 0; i < v; i++) {
        double theta = i == 0 ? 0 : i == v - 1 ? M_PI : M_PI * (1 + (i - 1) / SEGMENTS) / RINGS;
        double phi = i == 0 || i == v - 1 ? 0 : 2 * M_PI * ((i - 1) % SEGMENTS) / SEGMENTS;
        float n[3] = {(float)(sin(theta) * cos(phi)), (float)(sin(theta) * sin(phi)), (float)cos(theta)};
        for (int k = 0; k < 3; k++) {
            m.normals[3 * i + k] = n[k];
            m.positions[3 * i + k] = n[k] + (float)(k + 1);
            m.velocity[3 * i + k] = (float)(k + 1) * n[2];
        }
        m.speed[i] = 2.0f + n[2];
        m.density[i] = 1000.0f + n[0];
        m.id[i] = 3 * i + 7;
    }
    for (uint32_t s = 0; s < SEGMENTS; s++) {
        add_triangle(&m, 0, ring_vertex(1, s), ring_vertex(1, s + 1));
        add_triangle(&m, v - 1, ring_vertex(RINGS - 1, s + 1), ring_vertex(RINGS - 1, s));
        for (uint32_t r = 1; r + 1 < RINGS; r++) {
            uint32_t a = ring_vertex(r, s), b = ring_vertex(r + 1, s), c = ring_vertex(r + 1, s + 1),
                     d = ring_vertex(r, s + 1);
            add_triangle(&m, a, b, c);
            add_triangle(&m, a, c, d);
        }
    }
    return m;
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: %s DIR\n", argv[0]);
        return 2;
    }
    fc_surface_mesh m = sphere();
    static const char *const names[] = {"sphere.ply", "sphere.obj", "sphere.vtp", "sphere.stl"};
    char path[4096];
    fc_error err;
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        snprintf(path, sizeof path, "%s/%s", argv[1], names[i]);
        CHECK_CODE(fc_mesh_write_file(path, &m, &err), FC_OK);
    }
    snprintf(path, sizeof path, "%s/no_such_dir/sphere.ply", argv[1]);
    CHECK_CODE(fc_mesh_write_file(path, &m, &err), FC_ERR_IO);
    CHECK_MSG(strstr(err.message, "no_such_dir") != NULL, "%s", err.message);
    snprintf(path, sizeof path, "%s/sphere.off", argv[1]);
    CHECK_CODE(fc_mesh_write_file(path, &m, &err), FC_ERR_USAGE);
    CHECK(access(path, F_OK) != 0);
    /* An empty surface is a valid file too. */
    fc_surface_mesh none = {0};
    snprintf(path, sizeof path, "%s/empty.vtp", argv[1]);
    CHECK_CODE(fc_mesh_write_file(path, &none, &err), FC_OK);
    snprintf(path, sizeof path, "%s/empty.ply", argv[1]);
    CHECK_CODE(fc_mesh_write_file(path, &none, &err), FC_OK);
    printf("%u %u\n", (unsigned)m.vertex_count, (unsigned)m.triangle_count);
    fc_surface_mesh_free(&m);
    return test_result();
}
