/* aov_coverage.h — where a float image the CLI wrote (an --aov EXR) holds fluid,
 * as one flag per pixel: how the CLI tests compare framings (test_cli_up,
 * test_cli_framing) without depending on the shading. */
#ifndef FC_AOV_COVERAGE_H
#define FC_AOV_COVERAGE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* width x height flags (malloc'd, row by row): the first channel > 0. NULL
 * when the file is unreadable, not an EXR of that size, or memory runs out. */
bool *aov_coverage(const char *path, uint32_t width, uint32_t height);

/* Pixels set in one of two flag images of `pixels` pixels and not in the other. */
int coverage_difference(const bool *a, const bool *b, size_t pixels);

#endif
