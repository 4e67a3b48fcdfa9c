/* compute_splat.c — depth and thickness splat by compute shader and image atomics. */
#include "compute_splat.h"

#include <math.h>
#include <stdbool.h>

#include "anisotropy.h"
#include "fc_error.h"
#include "gl_util.h"
#include "pinhole_fill.h"
#include "shader_program.h"

/* Uniform locations fixed by layout(location) in surface_splat.comp.glsl and its libraries. */
enum {
    LOC_VIEW_MATRIX = 0,
    LOC_PROJECTION = 1,
    LOC_VIEWPORT = 2,
    LOC_RADIUS = 3,
    LOC_PARTICLE_COUNT = 6,
    LOC_UNITS_PER_CHORD = 7,
    LOC_MAX_CHORD = 8,
    LOC_FIRST_PARTICLE = 9,
    LOC_FLOOR_PLANE = 10,
    LOC_CULL_PHASE = 11,
    LOC_SLACK_PER_DEPTH = 12,
    LOC_THICKNESS_VIEWPORT = 13,
    LOC_FRONT_STRIDE = 14,
    LOC_SUN_MATRIX = 15,
    LOC_SUN_FOCAL = 19,
    LOC_SUN_VIEWPORT = 20,
    LOC_SIZED_PARTICLES = 512
};
/* The culling's steps in the splat, as surface_splat.comp.glsl's CULL_*. */
enum { CULL_NONE = 0, CULL_NEAR = 1, CULL_REST = 2 };
/* ... in the resolves (thickness_resolve.frag.glsl, depth_resolve.frag.glsl) and the
 * pinhole fill's compute shaders (fill_*.comp.glsl, pinhole_fill.comp.glsl). */
enum { LOC_CHORD_PER_UNIT = 0, LOC_SOURCE_SIZE = 40, LOC_REACH_TILES = 41, LOC_RESOLVE_SOURCE_SIZE = 52 };
enum {
    IMAGE_NEAREST_DEPTH = 0,
    IMAGE_THICKNESS_SUM = 1,
    IMAGE_DEPTH_OUT = 2,
    IMAGE_SUN_SUM = 3,
    IMAGE_FRONT_TILES = 4,
    IMAGE_FAR_TILES = 5,
    IMAGE_OCCUPIED_TILES = 6
};
enum { UNIT_POSITIONS = 0, UNIT_RADIUS_RATIOS = 1, UNIT_RESOLVED = 0 };
/* Storage buffer bindings: the ellipsoids in ellipsoid_shape.comp.glsl, the
 * fill's tiles in fill_candidates.comp.glsl and pinhole_fill.comp.glsl. */
enum { BIND_ELLIPSOIDS = 5, BIND_FILL_LIST = 0 };
/* The fill list's header: glDispatchComputeIndirect's three workgroup counts. */
enum { FILL_LIST_HEADER = 3 };
/* local_size of the shaders: the splat's, and the tiles' (splat_tiles.comp.glsl, fill_*.comp.glsl). */
enum { SPLAT_GROUP = 64, RESOLVE_TILE = 8 };
/* The culling's and the pinhole fill's tiles, pixels on a side (TILE_PX in
 * cull_tiles.glsl and fill_*.comp.glsl, local_size in pinhole_fill.comp.glsl). */
#define CULL_TILE_PX 4u
/* A particle counts as the fluid's front (walked before the culling) when its
 * centre lies within two bounding radii and this many tiles' extent (at its
 * depth) behind the nearest centre of its tile: a surface seen at a slant
 * recedes across a tile. More walks more particles first; fewer leaves holes
 * in the front, behind which nothing is culled. */
#define CULL_SLACK_TILES 2.0f
/* The front per tile is taken from every CULL_FRONT_STRIDE-th particle: it
 * only decides which particles are walked before the tiles' farthest depth
 * is taken (the culling stays exact whatever it holds), and a sample finds
 * a dense fluid's front about as well. 1M particles at 1024x768: the front
 * pass 140M -> 47M instructions, the near phase 368M -> 389M (strides 4, 5,
 * 8 measured a little worse, bench/RESULTS.md). */
#define CULL_FRONT_STRIDE 3u
/* Bytes per particle position: xyz as float32; per radius ratio: float32. */
enum { POSITION_BYTES = 3 * sizeof(float), RATIO_BYTES = sizeof(float) };
/* Workgroups along x per row of the dispatch: below the 65535 GL guarantees. */
#define SPLAT_GROUPS_PER_ROW 32768u

/* Thickness is summed in fixed point, as a share of the sphere's diameter
 * (no chord is longer; for ellipsoids, of the longest diameter one can
 * have, max_chord()). The worst case for one pixel is every particle of
 * the frame on it with its full diameter, so with U units per diameter the
 * sum stays below 2^32 as long as count * U < 2^32: U is chosen per render
 * from the count. Up to 256 particles U is 2^24 (the steps of a float's
 * mantissa; more would not be resolved); 64k particles still get 65535 units
 * (a rounding error of 1/131070 diameter per sphere), and the 16M particles a
 * frame may hold get 255 (1/510 of a diameter, under 0.1% of the thickness of
 * any pixel that many spheres cover). */
#define MAX_UNITS_PER_CHORD 16777216.0

static double units_per_chord(uint64_t particles)
{
    double fit = floor(4294967295.0 / (double)(particles ? particles : 1));
    return fit < MAX_UNITS_PER_CHORD ? fit : MAX_UNITS_PER_CHORD;
}

static uint64_t gcd(uint64_t a, uint64_t b)
{
    while (b) {
        uint64_t r = a % b;
        a = b;
        b = r;
    }
    return a;
}

/* The most particles one dispatch may read through a buffer texture of at
 * most max_texels texels, such that the next dispatch's first position sits
 * at an offset the driver accepts: a multiple of `alignment` bytes. */
static uint64_t dispatch_limit(GLint max_texels, GLint alignment)
{
    uint64_t align = alignment > 0 ? (uint64_t)alignment : 1;
    uint64_t step = align / gcd(align, POSITION_BYTES);   /* particles per aligned offset */
    uint64_t limit = (uint64_t)(max_texels > 0 ? max_texels : 0) / step * step;
    return limit > 0 ? limit : step;
}

/* The walks' libraries, by fc_splat_walk. */
static const char *const WALKS[FC_SPLAT_WALKS] = {"splat_walk_rows.glsl", "splat_walk_tiny.glsl",
                                                   "splat_walk_small.glsl"};

/* The preprocessor lines of each output (FC_THICKNESS_ONLY in surface_splat.comp.glsl). */
static const char *const OUTPUT_DEFINES[FC_SPLAT_OUTPUTS] = {
    NULL, "#define FC_THICKNESS_ONLY 1\n", "#define FC_DEPTH_ONLY 1\n",
    "#define FC_DEPTH_ONLY 1\n#define FC_FUSED_THICKNESS 1\n",
    "#define FC_DEPTH_ONLY 1\n#define FC_FUSED_THICKNESS 1\n#define FC_FUSED_SUN 1\n"};

/* The outputs that splat a reduced thickness in the culled depth's walk (spheres only). */
static bool fused_output(fc_splat_output output)
{
    return output == FC_SPLAT_DEPTH_AND_REDUCED_THICKNESS || output == FC_SPLAT_DEPTH_REDUCED_THICKNESS_AND_SUN;
}

/* A program of the particles' shape, spheres or ellipsoids (sphere_shape.comp.glsl,
 * ellipsoid_shape.comp.glsl), with its libraries and then the files `tail`. */
static fc_code build_shaped(const char *shader_dir, const char *defines, bool ellipsoids, const char *const *tail,
                            size_t tail_count, GLuint *program, fc_error *err)
{
    const char *spheres[] = {"sphere_bounds.glsl", "sphere_ray.glsl", "thickness_chord.glsl", "cull_tiles.glsl",
                             "sphere_shape.comp.glsl"};
    const char *shaped[] = {"sphere_bounds.glsl", "ellipsoid_bounds.glsl", "sphere_ray.glsl", "ellipsoid_ray.glsl",
                            "thickness_chord.glsl", "cull_tiles.glsl", "ellipsoid_shape.comp.glsl"};
    const char *files[sizeof shaped / sizeof shaped[0] + 2];
    const char *const *head = ellipsoids ? shaped : spheres;
    size_t count = ellipsoids ? sizeof shaped / sizeof shaped[0] : sizeof spheres / sizeof spheres[0];
    for (size_t k = 0; k < count; k++)
        files[k] = head[k];
    for (size_t k = 0; k < tail_count && count < sizeof files / sizeof files[0]; k++)
        files[count++] = tail[k];
    return fc_program_build_defines(shader_dir, defines, files, count, program, err);
}

/* The spheres' thickness alone with the walks for sprites of a few pixels:
 * FC_THICKNESS_FOOTPRINT in surface_splat.comp.glsl (the chord from the
 * projected ellipse instead of a ray cast per pixel). */
static const char FOOTPRINT_DEFINES[] = "#define FC_THICKNESS_ONLY 1\n#define FC_THICKNESS_FOOTPRINT 1\n";

static const char *splat_defines(fc_splat_output output, bool ellipsoids, fc_splat_walk walk)
{
    if (output == FC_SPLAT_THICKNESS_ONLY && !ellipsoids && walk != FC_SPLAT_WALK_ROWS)
        return FOOTPRINT_DEFINES;
    return OUTPUT_DEFINES[output];
}

/* The splat of spheres or of ellipsoids with each walk, for one output. */
static fc_code build_splats(const char *shader_dir, fc_splat_output output, bool ellipsoids,
                            GLuint programs[FC_SPLAT_WALKS], fc_error *err)
{
    for (int w = 0; w < FC_SPLAT_WALKS; w++) {
        const char *defines = splat_defines(output, ellipsoids, (fc_splat_walk)w);
        const char *tail[2];
        size_t files = 0;
        if (defines != FOOTPRINT_DEFINES)   /* the footprint visits its own kernel's pixels */
            tail[files++] = WALKS[w];
        tail[files++] = "surface_splat.comp.glsl";
        fc_code code = build_shaped(shader_dir, defines, ellipsoids, tail, files, &programs[w], err);
        if (code != FC_OK)
            return code;
    }
    return FC_OK;
}

/* The resolves: full-screen draws into the caller's R32F textures (depth_resolve.frag.glsl's comment says why). */
static fc_code build_resolves(const char *shader_dir, fc_compute_splat *s, fc_error *err)
{
    const char *depth[] = {"fullscreen.vert.glsl", "depth_resolve.frag.glsl"};
    const char *filling[] = {"fullscreen.vert.glsl", "pinhole_fill.glsl", "depth_resolve.frag.glsl"};
    const char *thickness[] = {"fullscreen.vert.glsl", "thickness_resolve.frag.glsl"};
    fc_code code = fc_program_build_defines(shader_dir, "#define FC_SPLAT_BITS 1\n#define FC_FILL_LISTED 1\n", depth,
                                            2, &s->depth_resolve_program, err);
    if (code == FC_OK)
        code = fc_program_build_defines(shader_dir, "#define FC_SPLAT_BITS 1\n", filling, 3,
                                        &s->filling_resolve_program, err);
    if (code == FC_OK)
        code = fc_program_build(shader_dir, thickness, 2, &s->thickness_resolve_program, err);
    if (code != FC_OK)
        return code;
    glCreateFramebuffers(1, &s->framebuffer);
    glCreateVertexArrays(1, &s->empty_vertex_array);
    return FC_OK;
}

fc_code fc_compute_splat_create(const char *shader_dir, fc_compute_splat *s, fc_error *err)
{
    *s = (fc_compute_splat){0};
    fc_code code = FC_OK;
    for (int o = 0; o < FC_SPLAT_OUTPUTS && code == FC_OK; o++) {
        code = build_splats(shader_dir, (fc_splat_output)o, false, s->splat_program[o], err);
        if (code == FC_OK && !fused_output((fc_splat_output)o))
            code = build_splats(shader_dir, (fc_splat_output)o, true, s->ellipsoid_program[o], err);
    }
    if (code == FC_OK)
        code = build_resolves(shader_dir, s, err);
    const char *tiles[] = {"tile_depths.glsl", "splat_tiles.comp.glsl"}, *front[] = {"splat_front.comp.glsl"};
    const char *occupancy[] = {"tile_depths.glsl", "fill_occupancy.comp.glsl"};
    const char *candidates[] = {"fill_candidates.comp.glsl"};
    const char *fill[] = {"pinhole_fill.glsl", "pinhole_fill.comp.glsl"};
    if (code == FC_OK)
        code = fc_program_build(shader_dir, tiles, 2, &s->tiles_program, err);
    if (code == FC_OK)
        code = fc_program_build(shader_dir, fill, 2, &s->fill_program, err);
    if (code == FC_OK)
        code = fc_program_build(shader_dir, occupancy, 2, &s->occupancy_program, err);
    if (code == FC_OK)
        code = fc_program_build(shader_dir, candidates, 1, &s->candidates_program, err);
    if (code == FC_OK)
        code = build_shaped(shader_dir, NULL, false, front, 1, &s->front_program, err);
    if (code == FC_OK)
        code = build_shaped(shader_dir, NULL, true, front, 1, &s->ellipsoid_front_program, err);
    if (code != FC_OK)
        return code;
    s->cull = s->fuse = s->fill_candidates = true;
    glCreateTextures(GL_TEXTURE_BUFFER, 1, &s->positions);
    glCreateTextures(GL_TEXTURE_BUFFER, 1, &s->ratios);
    GLint max_texels = 0, alignment = 1;
    glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &max_texels);
    glGetIntegerv(GL_TEXTURE_BUFFER_OFFSET_ALIGNMENT, &alignment);
    s->particles_per_dispatch = dispatch_limit(max_texels, alignment);
    return fc_gl_check("creating the compute splat's position texture", err);
}

static void release_images(fc_compute_splat *s)
{
    glDeleteTextures(1, &s->nearest_depth);
    glDeleteTextures(1, &s->thickness_sum);
    glDeleteTextures(1, &s->front_tiles);
    glDeleteTextures(1, &s->far_tiles);
    glDeleteTextures(1, &s->occupied_tiles);
    glDeleteBuffers(1, &s->fill_list);
    glDeleteTextures(1, &s->sun_sum);
    s->nearest_depth = s->thickness_sum = s->front_tiles = s->far_tiles = s->occupied_tiles = s->fill_list = 0;
    s->sun_sum = 0;
    s->width = s->height = s->sun_width = s->sun_height = 0;
}

void fc_compute_splat_destroy(fc_compute_splat *s)
{
    for (int o = 0; o < FC_SPLAT_OUTPUTS; o++) {
        for (int w = 0; w < FC_SPLAT_WALKS; w++) {
            glDeleteProgram(s->splat_program[o][w]);
            glDeleteProgram(s->ellipsoid_program[o][w]);
        }
    }
    glDeleteProgram(s->depth_resolve_program);
    glDeleteProgram(s->filling_resolve_program);
    glDeleteProgram(s->thickness_resolve_program);
    glDeleteProgram(s->fill_program);
    glDeleteFramebuffers(1, &s->framebuffer);
    glDeleteVertexArrays(1, &s->empty_vertex_array);
    glDeleteProgram(s->tiles_program);
    glDeleteProgram(s->occupancy_program);
    glDeleteProgram(s->candidates_program);
    glDeleteProgram(s->front_program);
    glDeleteProgram(s->ellipsoid_front_program);
    glDeleteTextures(1, &s->positions);
    glDeleteTextures(1, &s->ratios);
    release_images(s);
    *s = (fc_compute_splat){0};
}

static uint32_t tiles_across(uint32_t pixels)
{
    return (pixels + CULL_TILE_PX - 1) / CULL_TILE_PX;
}

/* The tile images' extent for images `pixels` across (fc_gl_non_pot: never a power of two). */
static uint32_t tile_extent(uint32_t pixels)
{
    return (uint32_t)fc_gl_non_pot(tiles_across(pixels));
}

/* The fill list's bytes for images of width x height. */
static GLsizeiptr fill_list_bytes(uint32_t width, uint32_t height)
{
    return (GLsizeiptr)(sizeof(GLuint) * (FILL_LIST_HEADER + (uint64_t)tiles_across(width) * tiles_across(height)));
}

/* Grows the images (per axis, never shrinking) until width x height fits, as render targets do. */
static fc_code reserve(fc_compute_splat *s, uint32_t width, uint32_t height, fc_error *err)
{
    if (s->nearest_depth && width <= s->width && height <= s->height)
        return FC_OK;
    width = fc_gl_grown_extent(width, s->width);
    height = fc_gl_grown_extent(height, s->height);
    release_images(s);
    s->allocations++;
    fc_code code = fc_gl_texture_create(GL_R32UI, width, height, false, &s->nearest_depth, err);
    if (code == FC_OK)
        code = fc_gl_texture_create(GL_R32UI, width, height, false, &s->thickness_sum, err);
    uint32_t tiles_x = tile_extent(width), tiles_y = tile_extent(height);
    if (code == FC_OK)
        code = fc_gl_texture_create(GL_R32UI, tiles_x, tiles_y, false, &s->front_tiles, err);
    if (code == FC_OK)
        code = fc_gl_texture_create(GL_R32UI, tiles_x, tiles_y, false, &s->far_tiles, err);
    if (code == FC_OK)
        code = fc_gl_texture_create(GL_R8UI, tiles_x, tiles_y, false, &s->occupied_tiles, err);
    if (code == FC_OK) {
        glCreateBuffers(1, &s->fill_list);
        glNamedBufferStorage(s->fill_list, fill_list_bytes(width, height), NULL, GL_DYNAMIC_STORAGE_BIT);
        code = fc_gl_check("creating the pinhole fill's tile list", err);
    }
    if (code != FC_OK) {
        release_images(s);
        return code;
    }
    s->width = width;
    s->height = height;
    return FC_OK;
}

/* Grows sun_sum (per axis, never shrinking) until the sun's view fits. */
static fc_code reserve_sun(fc_compute_splat *s, const fc_view *sun, fc_error *err)
{
    if (s->sun_sum && sun->width <= s->sun_width && sun->height <= s->sun_height)
        return FC_OK;
    uint32_t width = fc_gl_grown_extent(sun->width, s->sun_width);
    uint32_t height = fc_gl_grown_extent(sun->height, s->sun_height);
    glDeleteTextures(1, &s->sun_sum);
    s->sun_sum = 0;
    s->sun_width = s->sun_height = 0;
    s->allocations++;
    fc_code code = fc_gl_texture_create(GL_R32UI, width, height, false, &s->sun_sum, err);
    if (code != FC_OK)
        return code;
    s->sun_width = width;
    s->sun_height = height;
    return FC_OK;
}

/* Particles [first, first + count) in one dispatch, read through the buffer
 * texture: llvmpipe gathers a texel fetch for all lanes at once, where it
 * loads from a storage buffer lane by lane (bench/RESULTS.md, fifth round).
 * An invocation per particle, or (stride > 1, the front pass) per
 * stride-th particle. */
static void dispatch(const fc_compute_splat *s, GLuint program, const fc_particle_buffer *particles,
                     uint64_t first, uint64_t count, uint32_t stride)
{
    glTextureBufferRange(s->positions, GL_RGB32F, particles->buffer, (GLintptr)(first * POSITION_BYTES),
                         (GLsizeiptr)(count * POSITION_BYTES));
    /* first is a multiple of A / gcd(A, 12) (dispatch_limit), so for the
     * power-of-two alignments A drivers have, first x 4 bytes is aligned too. */
    if (particles->sized)
        glTextureBufferRange(s->ratios, GL_R32F, particles->radii, (GLintptr)(first * RATIO_BYTES),
                             (GLsizeiptr)(count * RATIO_BYTES));
    glProgramUniform1ui(program, LOC_PARTICLE_COUNT, (GLuint)count);
    if (particles->shapes)
        glProgramUniform1ui(program, LOC_FIRST_PARTICLE, (GLuint)first);
    uint64_t invocations = (count + stride - 1) / stride;
    GLuint groups = (GLuint)((invocations + SPLAT_GROUP - 1) / SPLAT_GROUP);
    GLuint per_row = groups < SPLAT_GROUPS_PER_ROW ? groups : SPLAT_GROUPS_PER_ROW;
    glDispatchCompute(per_row, (groups + per_row - 1) / per_row, 1);
}

/* The longest chord through a particle: its diameter, or the longest
 * ellipsoid's, of the largest particle. */
static float max_chord(const fc_particle_buffer *particles, float radius)
{
    return 2.0f * fc_anisotropy_reach(particles, radius);
}

/* Below this extent (pixels, along an axis) a box [centre - e/2 - 0.25,
 * centre + e/2 + 0.25] is shorter than 2 and holds at most two pixel centres;
 * a hair less, for the float arithmetic of the bounds. */
#define TINY_WALK_MAX_PX 1.49f
/* largest_px is r f / d; a sphere's exact silhouette is wider by 1 / sqrt(1 -
 * r^2 / d^2), which for spheres this small on screen stays far below this. */
#define SILHOUETTE_SLACK 1.02f
/* The nine-candidate walk while a typical box holds about three pixel
 * centres per axis. Measured on llvmpipe (bench/RESULTS.md): 17% less CPU
 * than the rows walk for sprites about 2 px across, 7% less at 2.85, 30%
 * more at about 4. */
#define SMALL_WALK_MAX_TYPICAL_PX 3.0f

static fc_splat_walk choose_walk(fc_splat_sprite sprite)
{
    if (sprite.largest_px * SILHOUETTE_SLACK < TINY_WALK_MAX_PX)
        return FC_SPLAT_WALK_TINY;
    if (sprite.typical_px > 0.0f && sprite.typical_px * SILHOUETTE_SLACK < SMALL_WALK_MAX_TYPICAL_PX)
        return FC_SPLAT_WALK_SMALL;
    return FC_SPLAT_WALK_ROWS;
}

/* Every particle (every stride-th) through `program`, in dispatches the buffer texture can show. */
static void dispatch_strided(const fc_compute_splat *s, GLuint program, const fc_particle_buffer *particles,
                             uint32_t stride)
{
    for (uint64_t first = 0; first < particles->count; first += s->particles_per_dispatch) {
        uint64_t left = particles->count - first;
        dispatch(s, program, particles, first, left < s->particles_per_dispatch ? left : s->particles_per_dispatch,
                 stride);
    }
}

static void dispatch_all(const fc_compute_splat *s, GLuint program, const fc_particle_buffer *particles)
{
    dispatch_strided(s, program, particles, 1);
}

/* The uniforms a program of the particles' shape reads (sphere_shape.comp.glsl,
 * ellipsoid_shape.comp.glsl, cull_tiles.glsl). */
static void set_shape_uniforms(GLuint program, const fc_particle_buffer *particles, const fc_view *view,
                               float radius)
{
    glProgramUniformMatrix4fv(program, LOC_VIEW_MATRIX, 1, GL_FALSE, view->view);
    glProgramUniform4f(program, LOC_PROJECTION, view->fx, view->fy, view->p22, view->p32);
    glProgramUniform2f(program, LOC_VIEWPORT, (float)view->width, (float)view->height);
    glProgramUniform1f(program, LOC_RADIUS, radius);
    glProgramUniform1i(program, LOC_SIZED_PARTICLES, particles->sized ? GL_TRUE : GL_FALSE);
}

/* The depth alone in the culling's steps (surface_splat.comp.glsl): the
 * tiles' front (from a sample), the particles near it, the farthest depth
 * per tile, the rest. */
static void dispatch_culled(const fc_compute_splat *s, GLuint near_program, GLuint program,
                            const fc_particle_buffer *particles, const fc_view *view, float radius)
{
    const GLuint nowhere = 0x7f800000u;   /* +inf bits */
    glClearTexImage(s->front_tiles, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &nowhere);
    glBindImageTexture(IMAGE_FRONT_TILES, s->front_tiles, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    GLuint front = particles->shapes ? s->ellipsoid_front_program : s->front_program;
    set_shape_uniforms(front, particles, view, radius);
    glProgramUniform1ui(front, LOC_FRONT_STRIDE, CULL_FRONT_STRIDE);
    glUseProgram(front);
    dispatch_strided(s, front, particles, CULL_FRONT_STRIDE);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);

    /* A tile's extent at depth d is d x CULL_TILE_PX x 2 / (fy x height) world units. */
    float tile_per_depth = (float)CULL_TILE_PX * 2.0f / (view->fy * (float)view->height);
    glProgramUniform1f(near_program, LOC_SLACK_PER_DEPTH, CULL_SLACK_TILES * tile_per_depth);
    glProgramUniform1f(program, LOC_SLACK_PER_DEPTH, CULL_SLACK_TILES * tile_per_depth);
    glProgramUniform1i(near_program, LOC_CULL_PHASE, CULL_NEAR);
    glBindImageTexture(IMAGE_FRONT_TILES, s->front_tiles, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32UI);
    glUseProgram(near_program);
    dispatch_all(s, near_program, particles);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);

    glUseProgram(s->tiles_program);
    glProgramUniform2i(s->tiles_program, LOC_SOURCE_SIZE, (GLint)view->width, (GLint)view->height);
    glBindImageTexture(IMAGE_FAR_TILES, s->far_tiles, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32UI);
    GLuint tiles_x = tiles_across(view->width), tiles_y = tiles_across(view->height);
    glDispatchCompute((tiles_x + RESOLVE_TILE - 1) / RESOLVE_TILE, (tiles_y + RESOLVE_TILE - 1) / RESOLVE_TILE, 1);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);

    glBindImageTexture(IMAGE_FAR_TILES, s->far_tiles, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32UI);
    glProgramUniform1i(program, LOC_CULL_PHASE, CULL_REST);
    glUseProgram(program);
    dispatch_all(s, program, particles);
}

/* `thickness_view`: the reduced view of FC_SPLAT_DEPTH_AND_REDUCED_THICKNESS's thickness, else NULL. */
/* The sun's view's uniforms (FC_FUSED_SUN in surface_splat.comp.glsl) and its sum's image. */
static void set_sun(const fc_compute_splat *s, GLuint program, const fc_view *sun)
{
    glProgramUniformMatrix4fv(program, LOC_SUN_MATRIX, 1, GL_FALSE, sun->view);
    glProgramUniform2f(program, LOC_SUN_FOCAL, sun->fx, sun->fy);
    glProgramUniform2f(program, LOC_SUN_VIEWPORT, (float)sun->width, (float)sun->height);
    glBindImageTexture(IMAGE_SUN_SUM, s->sun_sum, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
}

static void splat(fc_compute_splat *s, fc_splat_output output, const fc_particle_buffer *particles,
                  const fc_view *view, const fc_view *thickness_view, const fc_view *sun, float radius,
                  fc_splat_sprite sprite, const float *floor_plane, double units)
{
    fc_splat_walk walk = choose_walk(sprite);
    s->last_walk = walk;
    GLuint program = particles->shapes ? s->ellipsoid_program[output][walk] : s->splat_program[output][walk];
    set_shape_uniforms(program, particles, view, radius);
    glProgramUniform1f(program, LOC_UNITS_PER_CHORD, floor_plane ? (float)units : 0.0f);
    glProgramUniform1f(program, LOC_MAX_CHORD, max_chord(particles, radius));
    if (particles->shapes)
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BIND_ELLIPSOIDS, particles->shapes);
    if (floor_plane)
        glProgramUniform4fv(program, LOC_FLOOR_PLANE, 1, floor_plane);
    if (thickness_view)
        glProgramUniform2f(program, LOC_THICKNESS_VIEWPORT, (float)thickness_view->width,
                           (float)thickness_view->height);
    if (sun)
        set_sun(s, program, sun);
    glBindImageTexture(IMAGE_NEAREST_DEPTH, s->nearest_depth, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
    glBindImageTexture(IMAGE_THICKNESS_SUM, s->thickness_sum, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    glUseProgram(program);
    glBindTextureUnit(UNIT_POSITIONS, s->positions);
    glBindTextureUnit(UNIT_RADIUS_RATIOS, s->ratios);
    bool depth_alone = output == FC_SPLAT_DEPTH_ONLY || fused_output(output);
    if (depth_alone && s->cull) {
        /* The near phase has no thickness to splat: the depth's own program, without the fused code,
         * which llvmpipe would run masked. */
        GLuint near_program = program;
        if (fused_output(output)) {
            near_program = s->splat_program[FC_SPLAT_DEPTH_ONLY][walk];
            set_shape_uniforms(near_program, particles, view, radius);
        }
        dispatch_culled(s, near_program, program, particles, view, radius);
    } else {
        if (depth_alone)
            glProgramUniform1i(program, LOC_CULL_PHASE, CULL_NONE);
        dispatch_all(s, program, particles);
    }
    /* Detached, the texture does not keep a particle buffer alive once that
     * is reallocated. */
    glTextureBuffer(s->positions, GL_RGB32F, 0);
    glTextureBuffer(s->ratios, GL_R32F, 0);
    glBindTextureUnit(UNIT_POSITIONS, 0);
    glBindTextureUnit(UNIT_RADIUS_RATIOS, 0);
}

/* Lists the tiles where the pinhole fill's walks of `steps` texels may fill
 * a pixel: fill_occupancy.comp.glsl marks the tiles holding a splatted
 * depth, fill_candidates.comp.glsl lists those with one on all four sides
 * within reach. */
static void list_fill_tiles(const fc_compute_splat *s, const fc_view *view, int steps)
{
    GLuint tiles_x = tiles_across(view->width), tiles_y = tiles_across(view->height);
    GLuint groups_x = (tiles_x + RESOLVE_TILE - 1) / RESOLVE_TILE, groups_y = (tiles_y + RESOLVE_TILE - 1) / RESOLVE_TILE;
    const GLuint none_yet[FILL_LIST_HEADER] = {0, 1, 1};
    glNamedBufferSubData(s->fill_list, 0, sizeof none_yet, none_yet);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    glProgramUniform2i(s->occupancy_program, LOC_SOURCE_SIZE, (GLint)view->width, (GLint)view->height);
    glBindImageTexture(IMAGE_NEAREST_DEPTH, s->nearest_depth, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32UI);
    glBindImageTexture(IMAGE_OCCUPIED_TILES, s->occupied_tiles, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R8UI);
    glUseProgram(s->occupancy_program);
    glDispatchCompute(groups_x, groups_y, 1);
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    glProgramUniform2i(s->candidates_program, LOC_SOURCE_SIZE, (GLint)view->width, (GLint)view->height);
    glProgramUniform1i(s->candidates_program, LOC_REACH_TILES, (steps + (int)CULL_TILE_PX - 1) / (int)CULL_TILE_PX);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BIND_FILL_LIST, s->fill_list);
    glUseProgram(s->candidates_program);
    glDispatchCompute(groups_x, groups_y, 1);
    glMemoryBarrier(GL_COMMAND_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
}

/* A full-screen draw of `program` into `target` (R32F) over the view, reading `source` (R32UI). */
static void resolve_draw(const fc_compute_splat *s, GLuint program, const fc_view *view, GLuint source, GLuint target)
{
    glNamedFramebufferTexture(s->framebuffer, GL_COLOR_ATTACHMENT0, target, 0);
    glBindFramebuffer(GL_FRAMEBUFFER, s->framebuffer);
    glViewport(0, 0, (GLsizei)view->width, (GLsizei)view->height);
    /* Every texel written as the shader gives it, whatever an earlier pass left enabled. */
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_SCISSOR_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glUseProgram(program);
    glBindTextureUnit(UNIT_RESOLVED, source);
    fc_gl_draw_fullscreen(s->empty_vertex_array);
    glBindTextureUnit(UNIT_RESOLVED, 0);
}

/* The splatted depth into `depth`, pinholes filled (pinhole_fill.glsl):
 * the walks on the listed tiles only (s->fill_candidates), else at every
 * empty pixel. */
static void resolve_depth(const fc_compute_splat *s, const fc_view *view, float radius, GLuint depth)
{
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    int steps = fc_pinhole_fill_apply(s->fill_program, view, radius);
    fc_pinhole_fill_apply(s->filling_resolve_program, view, radius);
    GLuint program = s->fill_candidates ? s->depth_resolve_program : s->filling_resolve_program;
    glProgramUniform2i(program, LOC_RESOLVE_SOURCE_SIZE, (GLint)view->width, (GLint)view->height);
    if (s->fill_candidates && steps > 0)
        list_fill_tiles(s, view, steps);
    resolve_draw(s, program, view, s->nearest_depth, depth);
    if (s->fill_candidates && steps > 0) {
        /* The draw's pixels before the fill's stores over some of them. */
        glMemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        glProgramUniform2i(s->fill_program, LOC_SOURCE_SIZE, (GLint)view->width, (GLint)view->height);
        glBindImageTexture(IMAGE_NEAREST_DEPTH, s->nearest_depth, 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32UI);
        glBindImageTexture(IMAGE_DEPTH_OUT, depth, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BIND_FILL_LIST, s->fill_list);
        glUseProgram(s->fill_program);
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, s->fill_list);
        glDispatchComputeIndirect(0);
        glBindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
    }
    /* Later passes sample it as a texture, the readback reads it through a framebuffer. */
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
}

/* The thickness splatted into `sum`, `units` per chord of `longest_chord`, into `thickness` in world units. */
static void resolve_thickness(const fc_compute_splat *s, const fc_view *view, float longest_chord, double units,
                              GLuint sum, GLuint thickness)
{
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
    glProgramUniform1f(s->thickness_resolve_program, LOC_CHORD_PER_UNIT, (float)((double)longest_chord / units));
    resolve_draw(s, s->thickness_resolve_program, view, sum, thickness);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
}

fc_code fc_compute_splat_run(fc_compute_splat *s, const fc_particle_buffer *particles, const fc_view *view,
                             float radius, fc_splat_sprite sprite, const float *floor_plane, GLuint depth,
                             GLuint thickness, fc_error *err)
{
    if (!depth && !floor_plane)
        return fc_error_set(err, FC_ERR_USAGE, "compute splat: neither depth nor thickness wanted");
    fc_code code = reserve(s, view->width, view->height, err);
    if (code != FC_OK)
        return code;
    fc_splat_output output = !depth        ? FC_SPLAT_THICKNESS_ONLY
                             : floor_plane ? FC_SPLAT_DEPTH_AND_THICKNESS
                                           : FC_SPLAT_DEPTH_ONLY;
    const GLuint no_depth = 0x7f800000u, no_thickness = 0;   /* +inf bits, 0 */
    if (depth)
        glClearTexImage(s->nearest_depth, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &no_depth);
    if (floor_plane)
        glClearTexImage(s->thickness_sum, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &no_thickness);
    double units = units_per_chord(particles->count);
    s->last_fused = s->last_fused_sun = false;
    if (particles->count > 0)
        splat(s, output, particles, view, NULL, NULL, radius, sprite, floor_plane, units);
    if (depth)
        resolve_depth(s, view, radius, depth);
    if (floor_plane)
        resolve_thickness(s, view, max_chord(particles, radius), units, s->thickness_sum, thickness);
    return fc_gl_check("compute surface splat", err);
}

void fc_compute_splat_tally(const fc_compute_splat *s, fc_gpu_memory *m)
{
    uint64_t tiles = (uint64_t)tile_extent(s->width) * tile_extent(s->height);
    m->render_target_bytes += fc_gl_texel_bytes(GL_R32UI) * (2ull * s->width * s->height + 2ull * tiles) +
                              fc_gl_texel_bytes(GL_R8UI) * tiles +
                              (s->fill_list ? (uint64_t)fill_list_bytes(s->width, s->height) : 0) +
                              fc_gl_texel_bytes(GL_R32UI) * (uint64_t)s->sun_width * s->sun_height;
    m->allocations += s->allocations;
}

void fc_compute_splat_trim(fc_compute_splat *s)
{
    release_images(s);
}

bool fc_compute_splat_fuses(const fc_compute_splat *s, const fc_particle_buffer *particles,
                            fc_splat_sprite thickness_sprite)
{
    return s->fuse && !particles->shapes && choose_walk(thickness_sprite) != FC_SPLAT_WALK_ROWS;
}

bool fc_compute_splat_fuses_sun(const fc_compute_splat *s, const fc_particle_buffer *particles,
                                fc_splat_sprite sun_sprite)
{
    return s->fuse && !particles->shapes && choose_walk(sun_sprite) == FC_SPLAT_WALK_TINY;
}

fc_code fc_compute_splat_run_fused(fc_compute_splat *s, const fc_particle_buffer *particles, const fc_view *view,
                                   const fc_view *thickness_view, float radius, fc_splat_sprite sprite,
                                   const float *floor_plane, GLuint depth, GLuint thickness, const fc_sun_splat *sun,
                                   fc_error *err)
{
    if (!depth || !floor_plane || thickness_view->width > view->width || thickness_view->height > view->height)
        return fc_error_set(err, FC_ERR_USAGE, "fused splat: needs a depth, a floor plane and a smaller thickness");
    if (sun && (!sun->view || !sun->thickness))
        return fc_error_set(err, FC_ERR_USAGE, "fused splat: the sun needs a view and a texture");
    fc_code code = reserve(s, view->width, view->height, err);
    if (code == FC_OK && sun)
        code = reserve_sun(s, sun->view, err);
    if (code != FC_OK)
        return code;
    const GLuint no_depth = 0x7f800000u, no_thickness = 0;   /* +inf bits, 0 */
    glClearTexImage(s->nearest_depth, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &no_depth);
    glClearTexImage(s->thickness_sum, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &no_thickness);
    if (sun)
        glClearTexImage(s->sun_sum, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &no_thickness);
    double units = units_per_chord(particles->count);
    s->last_fused = true;
    s->last_fused_sun = sun != NULL;
    fc_splat_output output = sun ? FC_SPLAT_DEPTH_REDUCED_THICKNESS_AND_SUN : FC_SPLAT_DEPTH_AND_REDUCED_THICKNESS;
    if (particles->count > 0)
        splat(s, output, particles, view, thickness_view, sun ? sun->view : NULL, radius, sprite, floor_plane, units);
    resolve_depth(s, view, radius, depth);
    float chord = max_chord(particles, radius);
    resolve_thickness(s, thickness_view, chord, units, s->thickness_sum, thickness);
    if (sun)
        resolve_thickness(s, sun->view, chord, units, s->sun_sum, sun->thickness);
    return fc_gl_check("compute surface splat with the thickness", err);
}
