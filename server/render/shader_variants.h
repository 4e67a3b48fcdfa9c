/* shader_variants.h — programs built per combination of optional features.
 *
 * A software rasterizer (llvmpipe) runs both sides of every branch for every
 * pixel, even when a uniform makes all pixels take the same side: a feature a
 * render does not use (foam, noise, a cube map, a client background, mesh
 * shadows) costs as much as one it does. Built with the feature's switch as a
 * constant, the compiler removes what is off. Each feature has a define
 * (below), 1 or 0, that the shaders read under #ifdef FC_VARIANT; without it
 * (other programs that link the same files) the switch stays a uniform. */
#ifndef FC_SHADER_VARIANTS_H
#define FC_SHADER_VARIANTS_H

#include <epoxy/gl.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "fluidcast_types.h"
#include "shader_program.h"

/* The features and the defines the shaders see (1 or 0). */
typedef enum fc_shader_feature {
    FC_FEATURE_FLOOR = 1u << 0,            /* FC_HAS_FLOOR: the built-in floor (environment.frag.glsl) */
    FC_FEATURE_SHADOW = 1u << 1,           /* FC_HAS_SHADOW: the fluid's shadow on it */
    FC_FEATURE_MESH_SHADOW = 1u << 2,      /* FC_HAS_MESH_SHADOW: the opaque meshes' shadows */
    FC_FEATURE_CLIENT_IMAGE = 1u << 3,     /* FC_USE_CLIENT_IMAGE: a client's background (background.frag.glsl) */
    FC_FEATURE_ENVIRONMENT_MAP = 1u << 4,  /* FC_USE_ENVIRONMENT_MAP: a cube map reflected (composite.frag.glsl) */
    FC_FEATURE_FOAM = 1u << 5,             /* FC_HAS_FOAM: foam (composite.frag.glsl) */
    FC_FEATURE_COLORED = 1u << 6,          /* FC_COLORED: colour by attribute (composite.frag.glsl) */
    FC_FEATURE_NOISE = 1u << 7,            /* FC_HAS_NOISE: surface noise (surface_normal.frag.glsl) */
    FC_FEATURE_FLOOR_ONLY = 1u << 8,       /* FC_FLOOR_ONLY: every pixel sees the floor, no sky (background_regions.h) */
    FC_FEATURE_FLUID_MASK = 1u << 9        /* FC_FLUID_MASK: the background lays down the composite's stencil and
                                              the fluid's depth (background.frag.glsl, ARB_shader_stencil_export) */
} fc_shader_feature;

#define FC_SHADER_FEATURE_COUNT 10
/* Programs one cache keeps; a render uses up to four (background_regions.h), a session a few renders' worth. */
#define FC_PROGRAM_VARIANTS_MAX 12

typedef struct fc_program_variant {
    unsigned features;
    GLuint program;       /* 0: the slot is free */
    uint64_t uniforms;    /* its active uniform locations (fc_program_uniform_locations) */
} fc_program_variant;

/* The variants of one program (one list of shader files), built on first use. */
typedef struct fc_program_variants {
    char *shader_dir;                 /* owned copy; NULL: the built-in shaders */
    bool flat_constants;              /* uniforms as flat inputs (flat_constants.h) */
    const char *const *files;         /* static storage, not copied */
    size_t file_count;
    fc_program_variant slots[FC_PROGRAM_VARIANTS_MAX];
    size_t next_evicted;              /* when all slots are taken, round robin */
} fc_program_variants;

/* Remembers the files (which must outlive the cache), the shader directory
 * and whether the fragment stage's uniforms travel as flat inputs (`options`;
 * its defines are the features'), and builds the variant of `features` at
 * once, so that a shader that does not compile fails here rather than at the
 * first render. */
fc_code fc_program_variants_create(fc_program_variants *v, const fc_program_options *options,
                                   const char *const *files, size_t file_count, unsigned features, fc_error *err);
void fc_program_variants_destroy(fc_program_variants *v);

/* The program of `features`, built now if the cache lacks it. */
fc_code fc_program_variants_get(fc_program_variants *v, unsigned features, const fc_program_variant **out,
                                fc_error *err);

/* The defines of `features` as fc_program_build_defines takes them: FC_VARIANT
 * and every feature's define, 1 or 0; `out` holds at least
 * FC_SHADER_DEFINES_MAX bytes. */
#define FC_SHADER_DEFINES_MAX 512
void fc_shader_defines(unsigned features, char *out, size_t size);

#endif
