/* surface_cubes.c — the marching cubes tables of surface_cubes.h, made from
 * the face rule rather than typed in. */
#include "surface_cubes.h"

#include <string.h>

enum { NO_EDGE = 0xFF };

uint32_t fc_surface_cube_edge_corner(uint32_t k)
{
    uint32_t axis = k / 4u, j = k % 4u, seen = 0u;
    for (uint32_t code = 0; code < 8u; code++)
        if (!((code >> axis) & 1u) && seen++ == j)
            return code;
    return 0u;
}

/* The cell edge between two corners one axis apart. */
static uint32_t edge_between(uint32_t c0, uint32_t c1)
{
    uint32_t axis = (c0 ^ c1) == 1u ? 0u : (c0 ^ c1) == 2u ? 1u : 2u;
    uint32_t from = c0 < c1 ? c0 : c1;
    for (uint32_t j = 0; j < 4u; j++)
        if (fc_surface_cube_edge_corner(4u * axis + j) == from)
            return 4u * axis + j;
    return NO_EDGE;
}

static void corner_point(uint32_t code, float out[3])
{
    for (int a = 0; a < 3; a++)
        out[a] = (float)((code >> a) & 1u);
}

static void edge_midpoint(uint32_t k, float out[3])
{
    corner_point(fc_surface_cube_edge_corner(k), out);
    out[k / 4u] += 0.5f;
}

/* The segment from edge p to edge q on a face of outward normal n, directed so
 * that corner c (on the segment's inside side) lies on its right seen from
 * outside: (q - p) x (c - p) . n < 0. `inside` says whether c is inside. */
static void direct(uint8_t next[12], uint32_t p, uint32_t q, uint32_t c, int inside, const float n[3])
{
    float a[3], b[3], x[3], d[3], e[3];
    edge_midpoint(p, a);
    edge_midpoint(q, b);
    corner_point(c, x);
    for (int i = 0; i < 3; i++) {
        d[i] = b[i] - a[i];
        e[i] = x[i] - a[i];
    }
    float s = (d[1] * e[2] - d[2] * e[1]) * n[0] + (d[2] * e[0] - d[0] * e[2]) * n[1] + (d[0] * e[1] - d[1] * e[0]) * n[2];
    if ((s < 0.0f) == (inside != 0))
        next[p] = (uint8_t)q;
    else
        next[q] = (uint8_t)p;
}

/* The segments of one face (axis a, side s) for inside mask m, into next[]. */
static void face_segments(uint32_t m, uint32_t a, uint32_t s, uint8_t next[12])
{
    uint32_t b = (a + 1u) % 3u, c = (a + 2u) % 3u, ring[4];
    uint32_t base = s << a;
    ring[0] = base;
    ring[1] = base | 1u << b;
    ring[2] = base | 1u << b | 1u << c;
    ring[3] = base | 1u << c;
    float n[3] = {0, 0, 0};
    n[a] = s ? 1.0f : -1.0f;
    int in[4], count = 0;
    for (int i = 0; i < 4; i++)
        count += in[i] = (int)((m >> ring[i]) & 1u);
    if (count == 0 || count == 4)
        return;
    for (int i = 0; i < 4; i++) {
        int before = (i + 3) % 4, after = (i + 1) % 4;
        /* A corner alone on its side (its two neighbours on the other) is cut off; of two across a
         * diagonal (all four corners alone) only the inside ones, which keeps the outside connected. */
        if (in[before] != in[i] && in[after] != in[i] && (count != 2 || in[i]))
            direct(next, edge_between(ring[before], ring[i]), edge_between(ring[i], ring[after]), ring[i], in[i],
                   n);
    }
    if (count == 2 && in[0] != in[2]) {   /* two side by side: the segment across the face */
        uint32_t crossed[2], k = 0, inner = 0;
        for (int i = 0; i < 4; i++) {
            if (in[i] != in[(i + 1) % 4])
                crossed[k++] = edge_between(ring[i], ring[(i + 1) % 4]);
            if (in[i])
                inner = ring[i];
        }
        direct(next, crossed[0], crossed[1], inner, 1, n);
    }
}

/* Whether cell edges k and l lie on a common face of the cell: each edge lies
 * on the two faces (axis b, side of its corner's bit b) of the other axes. */
static int share_face(uint32_t k, uint32_t l)
{
    uint32_t ck = fc_surface_cube_edge_corner(k), cl = fc_surface_cube_edge_corner(l);
    for (uint32_t b = 0; b < 3u; b++)
        if (b != k / 4u && b != l / 4u && ((ck >> b) & 1u) == ((cl >> b) & 1u))
            return 1;
    return 0;
}

/* The loop's vertex to fan from: one none of whose diagonals joins two
 * vertices of one face. Such a diagonal lies in the face (an ambiguous one,
 * holding four vertices), where the cell across it could fan the same one:
 * the mesh edge would have four triangles. */
static uint32_t fan_start(const uint32_t *loop, uint32_t n)
{
    for (uint32_t r = 0; r < n; r++) {
        int clean = 1;
        for (uint32_t i = 2; i + 1 < n && clean; i++)
            clean = !share_face(loop[r], loop[(r + i) % n]);
        if (clean)
            return r;
    }
    return 0;
}

uint32_t fc_surface_cube_tables(uint32_t cases[FC_SURFACE_CUBE_CASES],
                                uint32_t triangles[FC_SURFACE_CUBE_TRIANGLES_MAX])
{
    uint32_t total = 0;
    for (uint32_t m = 0; m < FC_SURFACE_CUBE_CASES; m++) {
        uint8_t next[12];
        memset(next, NO_EDGE, sizeof next);
        for (uint32_t a = 0; a < 3u; a++)
            for (uint32_t s = 0; s < 2u; s++)
                face_segments(m, a, s, next);
        uint32_t first = total;
        int visited[12] = {0};
        for (uint32_t start = 0; start < 12u; start++) {
            if (next[start] == NO_EDGE || visited[start])
                continue;
            uint32_t loop[12], n = 0;
            for (uint32_t k = start; k < 12u && !visited[k]; k = next[k]) {
                visited[k] = 1;
                loop[n++] = k;
            }
            uint32_t r = fan_start(loop, n);
            for (uint32_t i = 1; i + 1 < n && total < FC_SURFACE_CUBE_TRIANGLES_MAX; i++)
                triangles[total++] = loop[r] | loop[(r + i) % n] << 4 | loop[(r + i + 1) % n] << 8;
        }
        cases[m] = first | (total - first) << 16;
    }
    return total;
}
