/* surface_tets.c — the marching tetrahedra tables of surface_tets.h, made
 * from the geometry rather than typed in: each triangle is oriented by its
 * normal at the edges' midpoints against the direction from the inside
 * vertices to the outside ones. A tetrahedron's cut never degenerates as the
 * vertices slide along their edges, so that orientation holds for every
 * interpolation. */
#include "surface_tets.h"

const uint8_t FC_SURFACE_TET_EDGES[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};

static const uint8_t axis_orders[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};

static void corner_point(uint32_t code, float out[3])
{
    for (int a = 0; a < 3; a++)
        out[a] = (float)((code >> a) & 1u);
}

static int edge_between(int v, int w)
{
    for (int k = 0; k < 6; k++)
        if ((FC_SURFACE_TET_EDGES[k][0] == v && FC_SURFACE_TET_EDGES[k][1] == w) ||
            (FC_SURFACE_TET_EDGES[k][0] == w && FC_SURFACE_TET_EDGES[k][1] == v))
            return k;
    return -1;
}

static void edge_midpoint(const uint32_t corner[4], int k, float out[3])
{
    float a[3], b[3];
    corner_point(corner[FC_SURFACE_TET_EDGES[k][0]], a);
    corner_point(corner[FC_SURFACE_TET_EDGES[k][1]], b);
    for (int i = 0; i < 3; i++)
        out[i] = 0.5f * (a[i] + b[i]);
}

/* The triangle's edges, swapped where needed so that its normal points from
 * the inside vertices (mask bits set) towards the outside ones. */
static uint32_t oriented(const uint32_t corner[4], unsigned mask, int e0, int e1, int e2)
{
    float p[3][3], in[3] = {0}, out[3] = {0};
    edge_midpoint(corner, e0, p[0]);
    edge_midpoint(corner, e1, p[1]);
    edge_midpoint(corner, e2, p[2]);
    for (int v = 0; v < 4; v++) {
        float c[3];
        corner_point(corner[v], c);
        for (int i = 0; i < 3; i++) {
            if (mask >> v & 1u)
                in[i] += c[i];
            else
                out[i] += c[i];
        }
    }
    int inside = __builtin_popcount(mask);
    float u[3], w[3], n[3], d[3];
    for (int i = 0; i < 3; i++) {
        u[i] = p[1][i] - p[0][i];
        w[i] = p[2][i] - p[0][i];
        d[i] = out[i] / (float)(4 - inside) - in[i] / (float)inside;
    }
    n[0] = u[1] * w[2] - u[2] * w[1];
    n[1] = u[2] * w[0] - u[0] * w[2];
    n[2] = u[0] * w[1] - u[1] * w[0];
    if (n[0] * d[0] + n[1] * d[1] + n[2] * d[2] < 0) {
        int t = e1;
        e1 = e2;
        e2 = t;
    }
    return (uint32_t)e0 | (uint32_t)e1 << 3 | (uint32_t)e2 << 6;
}

/* One tetrahedron's triangles for one inside mask. */
static uint32_t tet_case(const uint32_t corner[4], unsigned mask)
{
    int inside = __builtin_popcount(mask);
    if (inside == 0 || inside == 4)
        return 0;
    if (inside == 1 || inside == 3) {
        int lone = 0;   /* the vertex alone on its side */
        for (int v = 0; v < 4; v++)
            if (((mask >> v) & 1u) == (inside == 1 ? 1u : 0u))
                lone = v;
        int e[3], n = 0;
        for (int v = 0; v < 4; v++)
            if (v != lone)
                e[n++] = edge_between(lone, v);
        return 1u | oriented(corner, mask, e[0], e[1], e[2]) << 2;
    }
    int in[2], out[2], ni = 0, no = 0;
    for (int v = 0; v < 4; v++) {
        if (mask >> v & 1u)
            in[ni++] = v;
        else
            out[no++] = v;
    }
    /* The quad in[0]out[0], in[0]out[1], in[1]out[1], in[1]out[0], split along its first diagonal. */
    int q0 = edge_between(in[0], out[0]), q1 = edge_between(in[0], out[1]);
    int q2 = edge_between(in[1], out[1]), q3 = edge_between(in[1], out[0]);
    return 2u | oriented(corner, mask, q0, q1, q2) << 2 | oriented(corner, mask, q0, q2, q3) << 11;
}

void fc_surface_tet_tables(uint32_t corners[FC_SURFACE_TETS], uint32_t cases[FC_SURFACE_TETS * FC_SURFACE_TET_CASES])
{
    for (unsigned t = 0; t < FC_SURFACE_TETS; t++) {
        const uint8_t *order = axis_orders[t];
        uint32_t corner[4] = {0, 1u << order[0], (1u << order[0]) | (1u << order[1]), 7u};
        corners[t] = corner[0] | corner[1] << 3 | corner[2] << 6 | corner[3] << 9;
        for (unsigned m = 0; m < FC_SURFACE_TET_CASES; m++)
            cases[FC_SURFACE_TET_CASES * t + m] = tet_case(corner, m);
    }
}
