/* environment.h — the scene around the fluid (sky, floor, light) as the
 * full-screen shaders see it, derived from the camera and the frame bounds. */
#ifndef FC_ENVIRONMENT_H
#define FC_ENVIRONMENT_H

#include <epoxy/gl.h>
#include <stdbool.h>
#include <stdint.h>

#include "fluidcast_types.h"
#include "view.h"

typedef struct fc_environment {
    float up[3];              /* unit; the camera's up vector */
    float sun[3];             /* unit, towards the light, world space */
    float light_view[3];      /* the same direction in view space */
    float floor_u[3];         /* unit axes of the checker pattern in the floor plane */
    float floor_v[3];
    bool has_floor;           /* false: sky all around (a client background replaces floor and sky) */
    float floor_height;       /* the floor is dot(x, up) = floor_height */
    float floor_plane[4];     /* the floor in view space: dot(xyz, x) + w > 0 above it; (0,0,0,1) without */
    float checker_size;       /* world units */
    float pixel_angle;        /* radians one pixel spans at the image centre */
    float exposure_scale;     /* 2^settings.exposure */
    bool tone_map;            /* the filmic curve on the output (8-bit images); float images stay linear HDR */
    /* The fluid's shadow on the floor (shadow_pass.h); has_shadow false: none. */
    bool has_shadow;
    GLuint shadow_map;            /* R32F thickness along sun rays, world units */
    float shadow_transform[16];   /* world point -> (u w, v w, 0, w), (u, v) in [0, 1] over the map */
    float shadow_uv_scale[2];     /* the map's share of its texture */
    float shadow_uv_last[2];      /* the uv of its last texel centres */
    float shadow_box_lo[3];       /* a world box holding all that casts the shadow, blur included: */
    float shadow_box_hi[3];       /* sun rays that miss it leave the map's thickness 0 */
    float shadow_extinction[3];   /* per world unit of that thickness */
    GLuint fluid_sun_depth;       /* R32F the fluid's linear depth from the sun (shadow_pass.h), 0 = no fluid;
                                     the texture 0 where no mesh is drawn, the only reader */
    float fluid_sun_depth_uv_scale[2];
    /* The opaque meshes' shadows (mesh_pass.h), only with the fluid's. */
    bool has_mesh_shadow;
    GLuint mesh_sun_depth;        /* R32F the nearest mesh's linear depth from the sun */
    float mesh_sun_depth_uv_scale[2];
    float mesh_shadow_bias;       /* world units */
} fc_environment;

/* The environment of a render: a floor (when has_floor) perpendicular to the
 * camera's up vector touching the bottom of the particles' box [lo, hi]
 * (grown by the settings' radius), checkers scaled to the box, a sun high
 * behind the camera's right shoulder, the settings' exposure, and the tone map
 * when the image is 8-bit. */
void fc_environment_for_view(const fc_view *view, const fc_camera *cam, const float lo[3], const float hi[3],
                             const fc_settings *settings, bool has_floor, bool want_u8, fc_environment *env);

/* Sets the uniforms of camera.frag.glsl and environment.frag.glsl on the
 * program in use. */
void fc_environment_apply(const fc_environment *env, const fc_view *view);

/* The same, only those of the active locations `uniforms` (a shader variant's,
 * fc_program_uniform_locations). */
void fc_environment_apply_to(const fc_environment *env, const fc_view *view, uint64_t uniforms);

/* The shader variant features (shader_variants.h) this environment uses:
 * FC_FEATURE_FLOOR, FC_FEATURE_SHADOW, FC_FEATURE_MESH_SHADOW. */
unsigned fc_environment_features(const fc_environment *env);

#endif
