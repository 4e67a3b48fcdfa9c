/* mesh_write_stl.c — binary STL: an 80-byte header, the triangle count, and per
 * triangle its unit face normal (from its winding, counter-clockwise seen from
 * outside), its three corners and a zero attribute word. STL has no shared
 * vertices and no place for the attributes. */
#include <errno.h>
#include <math.h>
#include <string.h>

#include "fc_error.h"
#include "mesh_words.h"
#include "mesh_write.h"

#define STL_HEADER_SIZE 80

/* The unit normal of triangle (a, b, c); zero for a degenerate one. */
static void face_normal(const float *a, const float *b, const float *c, float n[3])
{
    float u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    n[0] = u[1] * v[2] - u[2] * v[1];
    n[1] = u[2] * v[0] - u[0] * v[2];
    n[2] = u[0] * v[1] - u[1] * v[0];
    float length = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; k++)
        n[k] = length > 0.0f ? n[k] / length : 0.0f;
}

static bool write_triangle(FILE *to, const fc_surface_mesh *m, uint64_t t)
{
    const uint32_t *f = m->indices + 3 * t;
    float record[12];
    const float *corner[3] = {m->positions + 3ull * f[0], m->positions + 3ull * f[1], m->positions + 3ull * f[2]};
    face_normal(corner[0], corner[1], corner[2], record);
    for (int k = 0; k < 3; k++)
        memcpy(record + 3 + 3 * k, corner[k], 12);
    const uint8_t attribute[2] = {0, 0};
    return fc_mesh_put_words(to, record, 12) && fwrite(attribute, 1, 2, to) == 2;
}

fc_code fc_mesh_write_stl(FILE *to, const fc_surface_mesh *mesh, fc_error *err)
{
    char header[STL_HEADER_SIZE];
    memset(header, ' ', sizeof header);
    /* Not "solid ...": readers take a header starting so for an ASCII file. */
    const char title[] = "fluidcast surface mesh (binary STL)";
    memcpy(header, title, sizeof title - 1);
    uint32_t count = mesh->triangle_count;
    bool ok = fwrite(header, 1, sizeof header, to) == sizeof header && fc_mesh_put_words(to, &count, 1);
    for (uint64_t t = 0; ok && t < mesh->triangle_count; t++)
        ok = write_triangle(to, mesh, t);
    return ok ? FC_OK : fc_error_set(err, FC_ERR_IO, "%s", strerror(errno));
}
