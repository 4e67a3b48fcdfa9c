/* pipeline.h — the screen-space fluid render pipeline (van der Laan et al. 2009),
 * independent of the network: tests and benchmarks drive it directly.
 *
 * Needs a current GL 4.5 core context (fc_gl_context). Not thread-safe: one
 * pipeline per GL context, used from the context's thread. */
#ifndef FC_PIPELINE_H
#define FC_PIPELINE_H

#include <stdbool.h>

#include "fluidcast_types.h"
#include "image.h"
#include "gpu_memory.h"

typedef struct fc_pipeline fc_pipeline;

/* How the full-screen passes' fragment shaders receive their per-draw values
 * (flat_constants.h). Both give the same images, bit for bit. */
typedef enum fc_constants_path {
    FC_CONSTANTS_AUTO = 0,   /* flat inputs on a software rasterizer (llvmpipe), uniforms on a GPU */
    FC_CONSTANTS_UNIFORMS,
    FC_CONSTANTS_FLAT
} fc_constants_path;

typedef struct fc_pipeline_config {
    const char *shader_dir;   /* NULL: shaders built into the binary; else load *.glsl from here (development) */
    fc_constants_path constants;
} fc_pipeline_config;

/* Compiles every shader; FC_ERR_GL with the info log of the first that fails. */
fc_code fc_pipeline_create(const fc_pipeline_config *config, fc_pipeline **out, fc_error *err);
void fc_pipeline_destroy(fc_pipeline *p);

/* Uploads a frame's particles to the GPU; they stay until the next upload, so
 * several cameras/settings can render the same frame. stage_ms (may be NULL)
 * receives FC_STAGE_UPLOAD. The frame must be validated (finite, radii in
 * (0, 1e6]) already. A frame with radii has its median radius found here, in
 * O(count) on a copy of the radii.
 * The particles go up in the frame's order: the first render with a
 * density_threshold > 0 sorts a frame with densities (densest first) and
 * rewrites them in that order, reading the frame again. So the frame's
 * arrays (not the fc_frame struct itself, which is copied) must stay valid
 * and unchanged until the next upload or fc_pipeline_destroy, or at least
 * until the last render of the frame. */
fc_code fc_pipeline_upload(fc_pipeline *p, const fc_frame *frame, float *stage_ms, fc_error *err);

/* fc_frame_estimate_radius of the uploaded frame, estimated at most once per
 * upload however often it is asked for: the render radius "auto" resolves to
 * it, and the spray classes and the anisotropy take their neighbourhoods
 * from it. */
float fc_pipeline_estimated_radius(fc_pipeline *p);

/* Renders the uploaded frame and reads back the image the request asks for:
 * FC_AOV_COLOR as RGBA (FC_PIXEL_U8 sRGB when `want_u8`, else FC_PIXEL_F32
 * linear), FC_AOV_NORMAL as three float channels (xyz), the other AOVs as one
 * float channel. `out` is reused across calls.
 * stage_ms (array of FC_STAGE_COUNT, may be NULL) receives GPU times of each
 * stage from timer queries (negative for stages that did not run).
 * settings->radius must be > 0 (the caller resolves "auto"), except for a
 * frame with per-particle radii: 0 then splats each particle at its own
 * radius, the median of them standing in where the passes need one size
 * (smoothing filter width, absorption per radius, ...), and a radius > 0
 * overrides them all (PROTOCOL.md 5). */
fc_code fc_pipeline_render(fc_pipeline *p, const fc_camera *camera, const fc_settings *settings,
                           fc_aov aov, int want_u8, fc_image *out, float *stage_ms, fc_error *err);

/* ---- Per-session inputs beyond the frame (owned by the caller, e.g. a daemon session) ---- */

/* GPU textures a client supplied for the scene: a background image (drawn behind
 * the fluid and refracted through it, instead of the built-in floor and sky) and
 * a cube map of six faces (reflected in the fluid, instead of the procedural sky).
 * Created through a pipeline, used only with that pipeline. */
typedef struct fc_scene_textures fc_scene_textures;

/* background: any size, RGBA or RGB, U8 sRGB or F32 linear; NULL = built-in scene.
 * faces: six square images of equal size in the order +X, -X, +Y, -Y, +Z, -Z
 * (OpenGL cube-map convention); NULL = procedural sky. */
fc_code fc_scene_textures_create(fc_pipeline *p, const fc_image *background, const fc_image *faces,
                                 fc_scene_textures **out, fc_error *err);
void fc_scene_textures_destroy(fc_scene_textures *t);

/* A client's triangle mesh on the GPU (PROTOCOL.md section 12), created
 * through a pipeline from a validated fc_mesh (its arrays are copied; the
 * mesh's colour, opacity, flags and transform are not kept: each render
 * names them, fc_scene_mesh). Owned by the caller like scene textures, not
 * counted in fc_pipeline_gpu_memory.
 * FC_ERR_RENDER when the GPU runs out of memory. */
typedef struct fc_mesh_buffers fc_mesh_buffers;
fc_code fc_mesh_buffers_create(fc_pipeline *p, const fc_mesh *mesh, fc_mesh_buffers **out, fc_error *err);
void fc_mesh_buffers_destroy(fc_mesh_buffers *b);

/* One mesh of a render, placed and coloured. */
typedef struct fc_scene_mesh {
    const fc_mesh_buffers *buffers;
    float transform[12];   /* 3x4 row-major, mesh frame -> world (fc_mesh.transform) */
    float color[3];        /* linear RGB */
    float opacity;         /* 1: opaque, drawn into the scene the fluid refracts, hiding the fluid behind it;
                              below 1: glass, blended over the fluid */
    bool hide_near;        /* faces whose front (counter-clockwise) side faces the camera are not drawn */
} fc_scene_mesh;

/* What surrounds the fluid in a render: scene textures (NULL: built-in) and
 * meshes (count 0: none). The view's depth range, the floor and the sun's
 * view of the shadows take the meshes' bounds in with the particles'. */
typedef struct fc_render_scene {
    const fc_scene_textures *textures;
    const fc_scene_mesh *meshes;
    uint32_t mesh_count;
} fc_render_scene;

/* Per-particle foam state across frames, keyed by particle id (CPU side): a
 * particle whose velocity changed by more than settings->foam_tau since its last
 * frame gets its noise amplitude raised; the raise decays by foam_decay per frame. */
typedef struct fc_foam_state fc_foam_state;
fc_code fc_foam_state_create(fc_foam_state **out, fc_error *err);
void fc_foam_state_destroy(fc_foam_state *s);
/* Advances the state by one frame and uploads each particle's amplitude
 * multiplier for the next renders of the uploaded frame (call after
 * fc_pipeline_upload with the same frame). Frames without ids or velocities get
 * the base amplitude everywhere. */
fc_code fc_foam_state_advance(fc_foam_state *s, fc_pipeline *p, const fc_frame *frame,
                              const fc_settings *settings, fc_error *err);
/* The multipliers the last advance gave the particles of its frame, in frame
 * order (one per particle); valid until the next advance. NULL before any. */
const float *fc_foam_state_amplitudes(const fc_foam_state *s);
/* Gives the uploaded frame's particles these multipliers (frame order, one per
 * particle): a frame uploaded again after others gets back what its advance
 * gave it, since one pipeline holds the amplitudes of one frame only. */
fc_code fc_pipeline_set_amplitudes(fc_pipeline *p, const float *amplitude, uint64_t count, fc_error *err);

/* Like fc_pipeline_render, with the session's scene textures (NULL = built-in). */
fc_code fc_pipeline_render_scene(fc_pipeline *p, const fc_camera *camera, const fc_settings *settings,
                                 const fc_scene_textures *scene, fc_aov aov, int want_u8, fc_image *out,
                                 float *stage_ms, fc_error *err);

/* Like fc_pipeline_render_scene, with meshes: opaque ones are drawn into the
 * scene before the fluid (the fluid's depth, and so every AOV but the
 * thickness, is cut where a mesh is nearer; the fluid refracts them; they cast
 * shadows on the floor and receive the fluid's when settings->shadow), glass
 * ones blended over the fluid after it. scene NULL: the built-in scene. */
fc_code fc_pipeline_render_with(fc_pipeline *p, const fc_camera *camera, const fc_settings *settings,
                                const fc_render_scene *scene, fc_aov aov, int want_u8, fc_image *out,
                                float *stage_ms, fc_error *err);

/* ---- GPU memory (see gpu_memory.h) ---- */

/* The GPU memory the pipeline holds now, from the sizes and formats its
 * resources were allocated with: particle buffers sized to the largest frame
 * uploaded (positions, and each particle's radius
 * ratio once a frame with radii came); render targets — the depth pass's raw depth, thickness and
 * linear depth (R32F each), the compute splat's two R32UI images, the
 * thickness splat and its blur (R32F x 3: the blur's two at half the
 * image's resolution, or the splat's where lower) and the thickness AOV's
 * upsampled copy (R32F), the shadow pass's own thickness splat and
 * blur of the sun's view (R32F x 3, a 256x256 map and its half-resolution
 * blur), the smoothing methods' ping-pong
 * pairs (curvature flow R32F, bilateral R32F, narrow range R32F, binomial
 * RGBA32F) and the narrow range's list of the 8x8 blocks that hold fluid (a
 * uint per block), the reduced-resolution depth pair (R32F) and the silhouette blend
 * (SRGB8_ALPHA8, RGBA32F), noise (R32F), normals (RGBA32F), background
 * (RGBA16F) and the composite (SRGB8_ALPHA8 and RGBA32F, each with a
 * DEPTH32F_STENCIL8 buffer) — each as wide as the widest and as high as the
 * highest image its stage ran for since it was allocated (targets only grow: a
 * smaller image draws into their lower-left corner, so alternating image sizes
 * allocate nothing); and the readback's pack buffer, sized to the largest
 * image read back. Scene textures belong to the caller and are not counted. */
void fc_pipeline_gpu_memory(const fc_pipeline *p, fc_gpu_memory *out);

/* Gives the render targets' GPU memory back (not the particle buffers or the
 * readback's pack buffer): the next render allocates what it uses at its
 * image size. For a caller that knows large images are over; never needed
 * for correctness, and no render calls it. */
void fc_pipeline_trim(fc_pipeline *p);

/* ---- Profiling, for the benchmark (see pass_profile.h) ---- */

/* One pass of a profiled render: its wall time with the GL queue drained
 * around it, the process's CPU time over the same span (on a software
 * rasterizer its worker threads' work on the pass, which other processes'
 * load stretches less than the wall time), and the fragment shader
 * invocations it ran (-1: not counted). */
typedef struct fc_pass_sample {
    const char *name;
    double ms;
    double cpu_ms;
    int64_t fragments;
} fc_pass_sample;

/* With profiling on, every render records its passes (and runs slower: the
 * queue is drained around each one). Off after fc_pipeline_create. */
void fc_pipeline_set_profiling(fc_pipeline *p, int on);

/* The passes of the last render, in order; their number (0 when profiling is off). */
int fc_pipeline_pass_profile(const fc_pipeline *p, const fc_pass_sample **samples);

#endif
