/* fc_frame_median.c — the median of a frame's per-particle radii: the one size
 * that stands for all of them where the renderer needs a single number (the
 * smoothing filter's width, the anisotropic kernel's reference size). */
#include "fc_frame.h"

#include <stdlib.h>
#include <string.h>

#include "fc_error.h"

static void swap(float *a, float *b)
{
    float t = *a;
    *a = *b;
    *b = t;
}

/* The k-th smallest of v[0..n) (Hoare's selection with a median-of-three
 * pivot), reordering v. Values are finite, so every comparison is ordered. */
static float select_kth(float *v, size_t n, size_t k)
{
    size_t lo = 0, hi = n - 1;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (v[mid] < v[lo])
            swap(&v[mid], &v[lo]);
        if (v[hi] < v[lo])
            swap(&v[hi], &v[lo]);
        if (v[hi] < v[mid])
            swap(&v[hi], &v[mid]);
        float pivot = v[mid];
        size_t i = lo, j = hi;
        while (i <= j) {
            while (v[i] < pivot)
                i++;
            while (pivot < v[j])
                j--;
            if (i <= j) {
                swap(&v[i], &v[j]);
                i++;
                if (j == 0)
                    break;
                j--;
            }
        }
        if (k <= j)
            hi = j;
        else if (k >= i)
            lo = i;
        else
            return v[k];
    }
    return v[k];
}

fc_code fc_frame_median_radius(const fc_frame *frame, float *median, fc_error *err)
{
    *median = 0.0f;
    if (!frame->radius || frame->count == 0)
        return FC_OK;
    if (frame->count > SIZE_MAX / sizeof(float))
        return fc_error_set(err, FC_ERR_NOMEM, "cannot copy %llu radii", (unsigned long long)frame->count);
    size_t n = (size_t)frame->count;
    float *copy = malloc(n * sizeof(float));
    if (!copy)
        return fc_error_set(err, FC_ERR_NOMEM, "cannot copy %zu radii to find their median", n);
    memcpy(copy, frame->radius, n * sizeof(float));
    *median = select_kth(copy, n, n / 2);
    free(copy);
    return FC_OK;
}
