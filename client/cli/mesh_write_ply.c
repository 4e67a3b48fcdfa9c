/* mesh_write_ply.c — binary little-endian PLY: one vertex element with the
 * position, normal and the mesh's attributes (speed, density, velocity as
 * vx vy vz, id), one face element of vertex index lists. */
#include <errno.h>
#include <string.h>

#include "fc_error.h"
#include "mesh_words.h"
#include "mesh_write.h"

#define RECORD_WORDS_MAX 12u     /* x y z nx ny nz speed density vx vy vz id */
#define VERTICES_PER_BLOCK 256u      /* records written per fwrite, from the stack */

static void print_header(FILE *to, const fc_surface_mesh *m)
{
    fprintf(to, "ply\nformat binary_little_endian 1.0\ncomment fluidcast surface mesh\n"
                "element vertex %u\nproperty float x\nproperty float y\nproperty float z\n"
                "property float nx\nproperty float ny\nproperty float nz\n",
            (unsigned)m->vertex_count);
    if (m->attributes & FC_SURFACE_SPEED)
        fputs("property float speed\n", to);
    if (m->attributes & FC_SURFACE_DENSITY)
        fputs("property float density\n", to);
    if (m->attributes & FC_SURFACE_VELOCITY)
        fputs("property float vx\nproperty float vy\nproperty float vz\n", to);
    if (m->attributes & FC_SURFACE_ID)
        fputs("property uint id\n", to);
    fprintf(to, "element face %u\nproperty list uchar uint vertex_indices\nend_header\n",
            (unsigned)m->triangle_count);
}

/* Vertex v's record into out; returns its words. */
static size_t vertex_record(const fc_surface_mesh *m, uint32_t v, uint32_t *out)
{
    size_t n = 0;
    memcpy(out + n, m->positions + 3ull * v, 12), n += 3;
    memcpy(out + n, m->normals + 3ull * v, 12), n += 3;
    if (m->speed)
        memcpy(out + n++, m->speed + v, 4);
    if (m->density)
        memcpy(out + n++, m->density + v, 4);
    if (m->velocity)
        memcpy(out + n, m->velocity + 3ull * v, 12), n += 3;
    if (m->id)
        out[n++] = m->id[v];
    return n;
}

static bool write_vertices(FILE *to, const fc_surface_mesh *m)
{
    uint32_t block[VERTICES_PER_BLOCK * RECORD_WORDS_MAX];
    for (uint32_t first = 0; first < m->vertex_count; first += VERTICES_PER_BLOCK) {
        size_t words = 0;
        for (uint32_t v = first; v < m->vertex_count && v < first + VERTICES_PER_BLOCK; v++)
            words += vertex_record(m, v, block + words);
        if (!fc_mesh_put_words(to, block, words))
            return false;
    }
    return true;
}

static bool write_faces(FILE *to, const fc_surface_mesh *m)
{
    const uint8_t three = 3;
    for (uint32_t t = 0; t < m->triangle_count; t++)
        if (fwrite(&three, 1, 1, to) != 1 || !fc_mesh_put_words(to, m->indices + 3ull * t, 3))
            return false;
    return true;
}

fc_code fc_mesh_write_ply(FILE *to, const fc_surface_mesh *mesh, fc_error *err)
{
    print_header(to, mesh);
    if (ferror(to) || !write_vertices(to, mesh) || !write_faces(to, mesh))
        return fc_error_set(err, FC_ERR_IO, "%s", strerror(errno));
    return FC_OK;
}
