/* flat_constants.h — a program's fragment-stage uniforms passed as flat inputs.
 *
 * Why: Mesa's llvmpipe (22.3, Debian 12) loads every uniform component a
 * fragment shader reads with a gather, lane by lane, for each 8 pixels it
 * shades: about 24 instructions per component where the arithmetic on it
 * costs one. The background and composite shaders read some 60 components
 * per pixel, half of the background pass's instructions (bench/RESULTS.md,
 * "Uniforms as flat inputs"). A flat input is set up once per triangle and
 * read as a constant. So, for programs built with flat constants, each
 * declaration of the form
 *
 *     layout(location = N) uniform TYPE NAME;   // comment
 *
 * in a fragment-stage file, TYPE a float or int scalar, vector or a mat3 /
 * mat4, becomes an input of the same name and type,
 *
 *     layout(location = L, component = C) flat in TYPE NAME;   // comment
 *
 * (one line for one, so the driver's line numbers stay the file's), and a
 * generated vertex-stage unit declares the uniform at location N and
 * `fc_forward_constants()`, which copies it to the matching flat output; the
 * program's vertex shader calls it under #ifdef FC_FLAT_CONSTANTS. Callers
 * set the uniforms by location as before. A flat input carries the vertex's
 * value unchanged, so the images are bit for bit the same
 * (test_flat_constants). Samplers, bools and arrays stay uniforms. The
 * fragment stage must have no inputs of its own (full-screen passes). */
#ifndef FC_FLAT_CONSTANTS_H
#define FC_FLAT_CONSTANTS_H

#include <stddef.h>

#include "fluidcast_types.h"

#define FC_FLAT_CONSTANTS_MAX 96
#define FC_FLAT_NAME_MAX 48

typedef struct fc_flat_constant {
    char type[8];               /* GLSL type name */
    char name[FC_FLAT_NAME_MAX];
    int location;               /* the uniform's */
    int slot;                   /* the input's location, -1: left a uniform (no room) */
    int component;              /* its first component there, -1 for a matrix (whole locations) */
} fc_flat_constant;

typedef struct fc_flat_constants {
    fc_flat_constant items[FC_FLAT_CONSTANTS_MAX];
    size_t count;
    int slots_used;
} fc_flat_constants;

/* Adds the uniform declarations of one fragment-stage source (`file` names it
 * in errors). A name seen before must have the same location and type.
 * FC_ERR_GL when it does not, when the source declares an input of its own,
 * or when there are more than FC_FLAT_CONSTANTS_MAX. */
fc_code fc_flat_constants_collect(fc_flat_constants *c, const char *source, const char *file, fc_error *err);

/* Gives each collected constant its input location and component, packing
 * scalars and vectors of one base type into shared locations, within
 * `max_slots` locations; those that do not fit stay uniforms. */
void fc_flat_constants_assign(fc_flat_constants *c, int max_slots);

/* `source` with the declarations of the assigned constants turned into flat
 * inputs, in a new buffer (*out, to free). */
fc_code fc_flat_constants_rewrite(const fc_flat_constants *c, const char *source, char **out, fc_error *err);

/* The vertex-stage unit that declares the uniforms and fc_forward_constants()
 * (a new buffer, *out, to free). */
fc_code fc_flat_constants_vertex_source(const fc_flat_constants *c, char **out, fc_error *err);

#endif
