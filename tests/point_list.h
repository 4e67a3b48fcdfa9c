/* point_list.h — a growing list of particle positions, for the tests that
 * build particle sets point by point (test_up_axis, test_framing_bounds). */
#ifndef FC_TEST_POINT_LIST_H
#define FC_TEST_POINT_LIST_H

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

typedef struct point_list {
    float *positions;    /* x y z per point; free() it */
    uint64_t count, capacity;
} point_list;

/* Appends (x, y, z), doubling the storage when full; exits on no memory (a test cannot go on). */
static inline void point_list_add(point_list *l, double x, double y, double z)
{
    if (l->count == l->capacity) {
        l->capacity = l->capacity ? 2 * l->capacity : 4096;
        l->positions = realloc(l->positions, l->capacity * 3 * sizeof *l->positions);
        if (!l->positions) {
            fprintf(stderr, "out of memory\n");
            exit(1);
        }
    }
    float *p = l->positions + 3 * l->count++;
    p[0] = (float)x;
    p[1] = (float)y;
    p[2] = (float)z;
}

#endif
