/* mesh_write_obj.c — Wavefront OBJ: v and vn lines (nine significant digits,
 * so the floats read back exactly) and f lines with 1-based indices, each
 * vertex naming its normal (f a//a b//b c//c). OBJ has no place for the
 * attributes. */
#include <errno.h>
#include <stdbool.h>
#include <string.h>

#include "fc_error.h"
#include "mesh_write.h"

static bool print_triples(FILE *to, const char *tag, const float *values, uint32_t count)
{
    for (uint64_t i = 0; i < count; i++) {
        const float *p = values + 3 * i;
        if (fprintf(to, "%s %.9g %.9g %.9g\n", tag, (double)p[0], (double)p[1], (double)p[2]) < 0)
            return false;
    }
    return true;
}

static bool print_faces(FILE *to, const fc_surface_mesh *m)
{
    for (uint64_t t = 0; t < m->triangle_count; t++) {
        const uint32_t *f = m->indices + 3 * t;
        unsigned a = f[0] + 1u, b = f[1] + 1u, c = f[2] + 1u;
        if (fprintf(to, "f %u//%u %u//%u %u//%u\n", a, a, b, b, c, c) < 0)
            return false;
    }
    return true;
}

fc_code fc_mesh_write_obj(FILE *to, const fc_surface_mesh *mesh, fc_error *err)
{
    bool ok = fprintf(to, "# fluidcast surface mesh: %u vertices, %u triangles\n", (unsigned)mesh->vertex_count,
                      (unsigned)mesh->triangle_count) >= 0 &&
              print_triples(to, "v", mesh->positions, mesh->vertex_count) &&
              print_triples(to, "vn", mesh->normals, mesh->vertex_count) && print_faces(to, mesh);
    return ok ? FC_OK : fc_error_set(err, FC_ERR_IO, "%s", strerror(errno));
}
