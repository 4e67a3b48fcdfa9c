/* test_util.h — the few assertion macros the C tests share. A failed CHECK prints
 * the file, line and condition (plus a formatted explanation) and marks the test
 * failed; the test's main returns test_result() so ctest sees the outcome. */
#ifndef FC_TEST_UTIL_H
#define FC_TEST_UTIL_H

#include <math.h>
#include <stdio.h>

static int test_failures_;

#define CHECK(cond) CHECK_MSG(cond, "%s", "")
#define CHECK_MSG(cond, ...)                                                       \
    do {                                                                           \
        if (!(cond)) {                                                             \
            test_failures_++;                                                      \
            fprintf(stderr, "%s:%d: CHECK failed: %s: ", __FILE__, __LINE__, #cond); \
            fprintf(stderr, __VA_ARGS__);                                          \
            fprintf(stderr, "\n");                                                 \
        }                                                                          \
    } while (0)
#define CHECK_NEAR(a, b, tol)                                                      \
    CHECK_MSG(fabs((double)(a) - (double)(b)) <= (double)(tol),                    \
              "%s = %g, %s = %g, tolerance %g", #a, (double)(a), #b, (double)(b), (double)(tol))
#define CHECK_CODE(expr, expected)                                                 \
    do {                                                                           \
        int got_ = (int)(expr);                                                    \
        CHECK_MSG(got_ == (int)(expected), "got code %d, expected %d", got_, (int)(expected)); \
    } while (0)

static inline int test_result(void)
{
    if (test_failures_)
        fprintf(stderr, "%d check(s) failed\n", test_failures_);
    return test_failures_ ? 1 : 0;
}

#endif
