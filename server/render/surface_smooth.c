/* surface_smooth.c — Taubin steps over each vertex's neighbours, listed once
 * from the triangles in a fixed order so that equal meshes smooth equally. */
#include "surface_smooth.h"

#include <stdlib.h>
#include <string.h>

#include "fc_error.h"

typedef struct neighbours {
    uint32_t *start;   /* vertex_count + 1 */
    uint32_t *of;      /* each triangle corner's next corner: in a closed, consistently oriented mesh (the
                          extraction's, by construction) every neighbour of a vertex follows it in exactly
                          one of its triangles, so each is listed once */
} neighbours;

static fc_code list_neighbours(const fc_surface_mesh *m, neighbours *n, fc_error *err)
{
    n->start = calloc((size_t)m->vertex_count + 1, sizeof *n->start);
    n->of = malloc(((size_t)m->triangle_count * 3 + 1) * sizeof *n->of);
    if (!n->start || !n->of)
        return fc_error_set(err, FC_ERR_NOMEM, "cannot allocate the neighbours of %u vertices", m->vertex_count);
    for (size_t i = 0; i < (size_t)m->triangle_count * 3; i++)
        n->start[m->indices[i] + 1]++;
    for (uint32_t v = 0; v < m->vertex_count; v++)
        n->start[v + 1] += n->start[v];
    uint32_t *fill = malloc(((size_t)m->vertex_count + 1) * sizeof *fill);
    if (!fill)
        return fc_error_set(err, FC_ERR_NOMEM, "cannot allocate the neighbours of %u vertices", m->vertex_count);
    memcpy(fill, n->start, ((size_t)m->vertex_count + 1) * sizeof *fill);
    for (size_t t = 0; t < m->triangle_count; t++) {
        const uint32_t *c = m->indices + 3 * t;
        for (int k = 0; k < 3; k++)
            n->of[fill[c[k]]++] = c[(k + 1) % 3];
    }
    free(fill);
    return FC_OK;
}

/* to = from + factor x (the neighbours' mean - from), for every vertex. */
static void laplacian_step(const neighbours *n, uint32_t vertices, float factor, const float *from, float *to)
{
    for (uint32_t v = 0; v < vertices; v++) {
        uint32_t first = n->start[v], last = n->start[v + 1];
        const float *x = from + 3 * (size_t)v;
        float *out = to + 3 * (size_t)v;
        if (last == first) {
            memcpy(out, x, 3 * sizeof *x);
            continue;
        }
        /* One walk over the neighbours for the three axes. */
        float sum[3] = {0.0f, 0.0f, 0.0f};
        for (uint32_t k = first; k < last; k++) {
            const float *y = from + 3 * (size_t)n->of[k];
            sum[0] += y[0];
            sum[1] += y[1];
            sum[2] += y[2];
        }
        for (int a = 0; a < 3; a++)
            out[a] = x[a] + factor * (sum[a] / (float)(last - first) - x[a]);
    }
}

fc_code fc_surface_smooth(fc_surface_mesh *mesh, uint32_t steps, fc_error *err)
{
    if (steps == 0 || mesh->vertex_count == 0)
        return FC_OK;
    neighbours n = {0};
    float *other = malloc((size_t)mesh->vertex_count * 3 * sizeof *other);
    fc_code code = other ? list_neighbours(mesh, &n, err)
                         : fc_error_set(err, FC_ERR_NOMEM, "cannot allocate %u smoothed vertices", mesh->vertex_count);
    if (code == FC_OK)
        for (uint32_t s = 0; s < steps; s++) {
            laplacian_step(&n, mesh->vertex_count, FC_TAUBIN_LAMBDA, mesh->positions, other);
            laplacian_step(&n, mesh->vertex_count, FC_TAUBIN_MU, other, mesh->positions);
        }
    free(other);
    free(n.start);
    free(n.of);
    return code;
}
