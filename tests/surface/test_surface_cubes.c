/* test_surface_cubes.c — the marching cubes tables (surface_cubes.h), case by
 * case: every crossed cell edge carries a vertex and no other edge does; no
 * triangle edge is directed the same way twice (the triangles of a case are
 * consistently oriented); no edge between two triangles of a case (a fan's
 * diagonal) joins two vertices of one face, where the cell across the face
 * could use it too and the mesh edge would have four triangles; and the lone
 * inside corner 0 gives one triangle, counter-clockwise seen from outside. */
#include <stdint.h>
#include <stdio.h>

#include "surface_cubes.h"
#include "test_util.h"

static int crossed(uint32_t mask, uint32_t k)
{
    uint32_t from = fc_surface_cube_edge_corner(k), to = from | 1u << (k / 4u);
    return ((mask >> from) & 1u) != ((mask >> to) & 1u);
}

static int on_one_face(uint32_t k, uint32_t l)
{
    uint32_t ck = fc_surface_cube_edge_corner(k), cl = fc_surface_cube_edge_corner(l);
    for (uint32_t b = 0; b < 3u; b++)
        if (b != k / 4u && b != l / 4u && ((ck >> b) & 1u) == ((cl >> b) & 1u))
            return 1;
    return 0;
}

static void check_case(uint32_t mask, const uint32_t *cases, const uint32_t *triangles)
{
    uint32_t first = cases[mask] & 0xFFFFu, count = cases[mask] >> 16;
    int used[12] = {0}, directed[12][12] = {{0}};
    for (uint32_t t = first; t < first + count; t++)
        for (uint32_t j = 0; j < 3u; j++) {
            uint32_t a = (triangles[t] >> (4u * j)) & 15u, b = (triangles[t] >> (4u * ((j + 1u) % 3u))) & 15u;
            CHECK_MSG(a < 12u && b < 12u, "case %u: edge %u or %u", mask, a, b);
            if (a >= 12u || b >= 12u)
                return;
            used[a] = 1;
            directed[a][b]++;
        }
    for (uint32_t k = 0; k < 12u; k++)
        CHECK_MSG(used[k] == crossed(mask, k), "case %u: edge %u crossed %d, used %d", mask, k, crossed(mask, k),
                  used[k]);
    for (uint32_t a = 0; a < 12u; a++)
        for (uint32_t b = 0; b < 12u; b++) {
            CHECK_MSG(directed[a][b] <= 1, "case %u: edge %u -> %u on %d triangles", mask, a, b, directed[a][b]);
            if (a < b && directed[a][b] && directed[b][a])
                CHECK_MSG(!on_one_face(a, b), "case %u: the diagonal %u - %u lies in a face", mask, a, b);
        }
}

int main(void)
{
    uint32_t cases[FC_SURFACE_CUBE_CASES], triangles[FC_SURFACE_CUBE_TRIANGLES_MAX];
    uint32_t total = fc_surface_cube_tables(cases, triangles), most = 0;
    for (uint32_t mask = 0; mask < FC_SURFACE_CUBE_CASES; mask++) {
        check_case(mask, cases, triangles);
        most = (cases[mask] >> 16) > most ? cases[mask] >> 16 : most;
    }
    CHECK(cases[0] >> 16 == 0 && cases[255] >> 16 == 0);
    /* Corner 0 alone inside: the x, y, z edges from it (cell edges 0, 4, 8), in that turn. */
    uint32_t lone = triangles[cases[1] & 0xFFFFu];
    CHECK_MSG(cases[1] >> 16 == 1 && (lone == 0x840u || lone == 0x084u || lone == 0x408u), "case 1: %03x", lone);
    printf("%u triangles in the 256 cases, at most %u a case\n", total, most);
    return test_result();
}
