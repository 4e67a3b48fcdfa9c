/* mesh_check.c — the measures of mesh_check.h. */
#include "mesh_check.h"

#include <stdlib.h>

static int compare_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return (x > y) - (x < y);
}

static uint32_t find(uint32_t *parent, uint32_t v)
{
    while (parent[v] != v)
        v = parent[v] = parent[parent[v]];
    return v;
}

mesh_topology mesh_check_topology(const fc_surface_mesh *m)
{
    mesh_topology t = {0};
    size_t f = m->triangle_count;
    uint64_t *directed = malloc((3 * f + 1) * sizeof *directed);
    uint32_t *parent = malloc(((size_t)m->vertex_count + 1) * sizeof *parent);
    uint8_t *used = calloc((size_t)m->vertex_count + 1, 1);
    for (uint32_t v = 0; v < m->vertex_count; v++)
        parent[v] = v;
    for (size_t i = 0; i < f; i++)
        for (int k = 0; k < 3; k++) {
            uint32_t a = m->indices[3 * i + k], b = m->indices[3 * i + (k + 1) % 3];
            directed[3 * i + k] = (uint64_t)a << 32 | b;
            used[a] = 1;
            parent[find(parent, a)] = find(parent, b);
        }
    qsort(directed, 3 * f, sizeof *directed, compare_u64);
    t.closed_manifold = true;
    for (size_t i = 0; i < 3 * f; i++) {
        uint64_t e = directed[i], reverse = e << 32 | e >> 32;
        if ((i > 0 && directed[i - 1] == e) || (e >> 32) == (e & 0xffffffffu) ||
            !bsearch(&reverse, directed, 3 * f, sizeof *directed, compare_u64))
            t.closed_manifold = false;
    }
    t.edges = 3 * f / 2;
    for (uint32_t v = 0; v < m->vertex_count; v++) {
        t.unused_vertices += !used[v];
        t.components += used[v] && find(parent, v) == v;
    }
    t.euler = (int64_t)(m->vertex_count - t.unused_vertices) - (int64_t)t.edges + (int64_t)f;
    free(directed);
    free(parent);
    free(used);
    return t;
}

static void corner(const fc_surface_mesh *m, size_t tri, int k, double out[3])
{
    const float *p = m->positions + 3 * (size_t)m->indices[3 * tri + k];
    for (int a = 0; a < 3; a++)
        out[a] = p[a];
}

static void face_normal(const fc_surface_mesh *m, size_t tri, double n[3], double centroid[3])
{
    double a[3], b[3], c[3];
    corner(m, tri, 0, a);
    corner(m, tri, 1, b);
    corner(m, tri, 2, c);
    double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    n[0] = u[1] * w[2] - u[2] * w[1];
    n[1] = u[2] * w[0] - u[0] * w[2];
    n[2] = u[0] * w[1] - u[1] * w[0];
    for (int i = 0; i < 3; i++)
        centroid[i] = (a[i] + b[i] + c[i]) / 3.0;
}

double mesh_volume(const fc_surface_mesh *m)
{
    double v = 0.0;
    for (size_t t = 0; t < m->triangle_count; t++) {
        double n[3], c[3];
        face_normal(m, t, n, c);
        v += (n[0] * c[0] + n[1] * c[1] + n[2] * c[2]) / 6.0;
    }
    return v;
}

double mesh_mean_distance(const fc_surface_mesh *m, const double c[3])
{
    double sum = 0.0;
    for (size_t v = 0; v < m->vertex_count; v++) {
        double d2 = 0.0;
        for (int a = 0; a < 3; a++) {
            double d = m->positions[3 * v + a] - c[a];
            d2 += d * d;
        }
        sum += __builtin_sqrt(d2);
    }
    return m->vertex_count ? sum / m->vertex_count : 0.0;
}

double mesh_outward_faces(const fc_surface_mesh *m, const double c[3])
{
    size_t out = 0;
    for (size_t t = 0; t < m->triangle_count; t++) {
        double n[3], g[3];
        face_normal(m, t, n, g);
        out += n[0] * (g[0] - c[0]) + n[1] * (g[1] - c[1]) + n[2] * (g[2] - c[2]) > 0.0;
    }
    return m->triangle_count ? (double)out / m->triangle_count : 0.0;
}

double mesh_normals_agree(const fc_surface_mesh *m)
{
    double *sum = calloc((size_t)m->vertex_count * 3 + 1, sizeof *sum);
    for (size_t t = 0; t < m->triangle_count; t++) {
        double n[3], g[3];
        face_normal(m, t, n, g);
        for (int k = 0; k < 3; k++)
            for (int a = 0; a < 3; a++)
                sum[3 * (size_t)m->indices[3 * t + k] + a] += n[a];
    }
    size_t agree = 0;
    for (size_t v = 0; v < m->vertex_count; v++) {
        double dot = 0.0;
        for (int a = 0; a < 3; a++)
            dot += m->normals[3 * v + a] * sum[3 * v + a];
        agree += dot > 0.0;
    }
    free(sum);
    return m->vertex_count ? (double)agree / m->vertex_count : 0.0;
}
