/* surface_mesher.c — the surface mesh of a frame (surface_mesher.h): the grid and
 * the particles' bins on the CPU (surface_grid.c), then the compute passes:
 * the field at the blocks' samples; the blocks the surface crosses kept with
 * their field; the crossed lattice edges counted and
 * prefix-summed into vertex numbers; the cells' triangles counted and
 * prefix-summed; each vertex's edge written; the vertices written, one
 * invocation each; the triangles written (marching cubes, surface_cubes.h). No atomics anywhere: every output's place comes
 * from a prefix sum over blocks in key order, so equal input gives the same
 * arrays bit for bit. Then Taubin smoothing on the CPU (surface_smooth.c). */
#include "surface_mesher.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "fc_settings.h"
#include "gl_util.h"
#include "surface_cubes.h"
#include "surface_grid.h"
#include "surface_passes.h"
#include "surface_smooth.h"

/* Uniform locations of surface_*.comp.glsl. */
enum { LOC_BLOCKS = 0, LOC_ORIGIN = 1, LOC_CELL = 2, LOC_ISO = 3, LOC_KERNEL = 4, LOC_EMIT = 5, LOC_BIN = 6,
       LOC_BINS = 7, LOC_WITH_ATTRIBUTES = 8, LOC_VERTEX_COUNT = 9, LOC_STAGE = 10 };
/* Shader storage bindings of surface_*.comp.glsl. */
enum { BIND_PARTICLES = 0, BIND_ATTRIBUTES = 1, BIND_IDS = 2, BIND_KEYS = 3, BIND_BIN_STARTS = 4,
       BIND_CROSSED = 5, BIND_FIELD = 6, BIND_VERTEX_EDGES = 7, BIND_CUBES = 8, BIND_SHAPES = 9, BIND_EDGES = 10,
       BIND_CELLS = 11, BIND_POSITIONS = 12, BIND_NORMALS = 13, BIND_VERTEX_ATTRIBUTES = 14,
       BIND_VERTEX_EXTRAS = 15, BIND_INDICES = 16 };
enum { BUFFER_COUNT = 17 };

/* Bytes of one output vertex on the GPU (its edge, position, normal, attributes, speed and id) and of one
 * triangle. */
#define VERTEX_BYTES 52u
#define TRIANGLE_BYTES 12u

typedef struct extraction {
    fc_surface_grid grid;
    float iso;
    int kernel;
    int with_attributes;   /* the frame has attributes for the vertices (mesh_attributes) */
    uint32_t vertices, triangles;
    GLuint buffers[BUFFER_COUNT];
} extraction;

float fc_surface_kernel_reach_radii(fc_surface_kernel kernel)
{
    return kernel == FC_SURFACE_KERNEL_SPH ? FC_SURFACE_SPH_REACH_RADII : FC_SURFACE_METABALL_REACH_RADII;
}

/* The field of one particle of radius 1 at distance `d` (in radii): 1 at
 * the centre, 0 from its reach on; as weight() in surface_kernel.comp.glsl. */
static float kernel_weight(fc_surface_kernel kernel, float d)
{
    float reach = fc_surface_kernel_reach_radii(kernel);
    if (d >= reach)
        return 0.0f;
    if (kernel != FC_SURFACE_KERNEL_SPH) {   /* Wyvill's soft objects: (1 - d^2 / R^2)^3 */
        float q = 1.0f - d * d / (reach * reach);
        return q * q * q;
    }
    float q = d / (0.5f * reach);            /* the cubic spline, 1 at the centre, q = d / h in [0, 2) */
    return q < 1.0f ? 1.0f - 1.5f * q * q + 0.75f * q * q * q : 0.25f * (2.0f - q) * (2.0f - q) * (2.0f - q);
}

/* A lone particle's field at one radius: its surface is its sphere. */
static float iso_of(fc_surface_kernel kernel)
{
    return kernel_weight(kernel, 1.0f);
}

static fc_code make_buffer(GLuint *buffer, uint64_t bytes, const void *data, fc_error *err)
{
    glCreateBuffers(1, buffer);
    glNamedBufferStorage(*buffer, (GLsizeiptr)(bytes ? bytes : 16), bytes ? data : NULL, GL_DYNAMIC_STORAGE_BIT);
    return fc_gl_check("allocating the surface mesh buffers", err);
}

/* The particles as the field pass reads them, in the grid's bin order: centre (the ellipsoid's
 * smoothed one with the anisotropic kernel) and radius, velocity and density,
 * id (the index where the frame has none); and the ellipsoids' G as two vec4
 * (xx xy xz yy, yz zz), or one unused vec4 for the other kernels. */
static fc_code upload_particles(extraction *x, const fc_frame *frame, const float *centres,
                                const fc_ellipsoid *ellipsoids, const float *radius, float uniform_radius,
                                fc_error *err)
{
    size_t n = (size_t)frame->count, shapes_n = ellipsoids ? 2 * n : 1;
    const uint32_t *order = x->grid.order;
    float *particles = malloc(n * 16), *attributes = calloc(n, 16), *shapes = calloc(shapes_n, 16);
    uint32_t *ids = malloc(n * 4);
    fc_code code = FC_OK;
    if (!particles || !attributes || !ids || !shapes)
        code = fc_error_set(err, FC_ERR_NOMEM, "cannot stage %zu particles for the surface mesh", n);
    for (size_t i = 0; code == FC_OK && ellipsoids && i < n; i++)
        memcpy(shapes + 8 * i, ellipsoids[order[i]].inverse, 6 * sizeof(float));
    for (size_t i = 0; code == FC_OK && i < n; i++) {
        size_t p = order[i];
        memcpy(particles + 4 * i, centres + 3 * p, 12);
        particles[4 * i + 3] = radius ? radius[p] : uniform_radius;
        if (frame->velocity)
            memcpy(attributes + 4 * i, frame->velocity + 3 * p, 12);
        if (frame->density)
            attributes[4 * i + 3] = frame->density[p];
        ids[i] = frame->ids ? frame->ids[p] : (uint32_t)p;
    }
    if (code == FC_OK)
        code = make_buffer(&x->buffers[BIND_PARTICLES], n * 16, particles, err);
    if (code == FC_OK)
        code = make_buffer(&x->buffers[BIND_ATTRIBUTES], n * 16, attributes, err);
    if (code == FC_OK)
        code = make_buffer(&x->buffers[BIND_IDS], n * 4, ids, err);
    if (code == FC_OK)
        code = make_buffer(&x->buffers[BIND_SHAPES], shapes_n * 16, shapes, err);
    free(shapes);
    free(particles);
    free(attributes);
    free(ids);
    return code;
}

/* The grid's bins and the passes' work buffers. */
/* The grid's blocks and their field: keys, the particles' bins, a sample's value each, a crossed flag each. */
static fc_code allocate_grid(extraction *x, fc_error *err)
{
    const fc_surface_grid *g = &x->grid;
    uint64_t blocks = g->block_count;
    fc_code code = make_buffer(&x->buffers[BIND_KEYS], blocks * 4, g->block_keys, err);
    uint64_t bins = (uint64_t)g->bins[0] * g->bins[1] * g->bins[2];
    if (code == FC_OK)
        code = make_buffer(&x->buffers[BIND_BIN_STARTS], (bins + 1) * 4, g->bin_starts, err);
    if (code == FC_OK)
        code = make_buffer(&x->buffers[BIND_FIELD], blocks * FC_SURFACE_BLOCK_SAMPLES * 4, NULL, err);
    if (code == FC_OK)
        code = make_buffer(&x->buffers[BIND_CROSSED], blocks * 4, NULL, err);
    return code;
}

/* The prefix sums' entries of the (crossed) blocks' edges and cells. */
static fc_code allocate_scans(extraction *x, fc_error *err)
{
    uint64_t blocks = x->grid.block_count;
    fc_code code = make_buffer(&x->buffers[BIND_EDGES],
                               fc_surface_scan_entries(blocks * FC_SURFACE_BLOCK_EDGES) * 4, NULL, err);
    if (code == FC_OK)
        code = make_buffer(&x->buffers[BIND_CELLS],
                           fc_surface_scan_entries(blocks * FC_SURFACE_BLOCK_CELLS) * 4, NULL, err);
    return code;
}

static void delete_buffer(extraction *x, int binding)
{
    glDeleteBuffers(1, &x->buffers[binding]);
    x->buffers[binding] = 0;
}

static void bind_all(const extraction *x)
{
    for (GLuint b = 0; b < BUFFER_COUNT; b++)
        if (x->buffers[b])
            glBindBufferBase(GL_SHADER_STORAGE_BUFFER, b, x->buffers[b]);
}

/* The uniforms each program declares (setting one a program lacks is an error). */
enum { USES_PLACE = 1, USES_ISO = 2, USES_KERNEL = 4, USES_EMIT = 8, USES_BINS = 16 };

static void set_grid_uniforms(GLuint program, unsigned uses, const extraction *x, int emit)
{
    glProgramUniform1ui(program, LOC_BLOCKS, x->grid.block_count);
    if (uses & USES_PLACE) {
        glProgramUniform3fv(program, LOC_ORIGIN, 1, x->grid.origin);
        glProgramUniform1f(program, LOC_CELL, x->grid.cell);
    }
    if (uses & USES_ISO)
        glProgramUniform1f(program, LOC_ISO, x->iso);
    if (uses & USES_KERNEL)
        glProgramUniform1i(program, LOC_KERNEL, x->kernel);
    if (uses & USES_EMIT)
        glProgramUniform1i(program, LOC_EMIT, emit);
    if (uses & USES_BINS) {
        glProgramUniform1f(program, LOC_BIN, x->grid.bin);
        glProgramUniform3uiv(program, LOC_BINS, 1, x->grid.bins);
    }
}

static void run_program(const fc_surface_passes *s, GLuint program, unsigned uses, const extraction *x, int emit)
{
    set_grid_uniforms(program, uses, x, emit);
    glUseProgram(program);
    bind_all(x);
    fc_surface_dispatch_blocks(s, x->grid.block_count);
}

/* The field pass's two stages (surface_field.comp.glsl): the samples each block owns proven at or above the
 * iso value where they are, then the field of every block not solid. */
static void run_field(const fc_surface_passes *s, const extraction *x)
{
    for (int stage = 0; stage < 2; stage++) {
        glProgramUniform1i(s->field_program, LOC_STAGE, stage);
        run_program(s, s->field_program, USES_PLACE | USES_ISO | USES_KERNEL | USES_BINS, x, 0);
    }
}

static void run_crossed(const fc_surface_passes *s, const extraction *x)
{
    run_program(s, s->crossed_program, USES_ISO, x, 0);
}

/* Copies the field of the kept blocks (crossed[b] != 0, in order) from `all` into `kept`, a run of
 * consecutive blocks at a time. */
static void copy_kept_field(GLuint all, GLuint kept, const uint32_t *crossed, uint32_t blocks)
{
    const GLsizeiptr block_bytes = (GLsizeiptr)FC_SURFACE_BLOCK_SAMPLES * 4;
    uint32_t to = 0;
    for (uint32_t b = 0; b < blocks;) {
        if (!crossed[b]) {
            b++;
            continue;
        }
        uint32_t end = b;
        while (end < blocks && crossed[end])
            end++;
        glCopyNamedBufferSubData(all, kept, (GLintptr)b * block_bytes, (GLintptr)to * block_bytes,
                                 (GLsizeiptr)(end - b) * block_bytes);
        to += end - b;
        b = end;
    }
}

/* Keeps the blocks the surface crosses (surface_crossed.comp.glsl), in key
 * order, with their field: the edges, cells and vertices only ever need
 * those, and the scans over every block of the grid (most of them inside the
 * fluid or in the air around it) were most of its memory and time. */
static fc_code keep_crossed_blocks(const fc_surface_passes *s, extraction *x, fc_error *err)
{
    fc_surface_grid *g = &x->grid;
    uint32_t blocks = g->block_count;
    run_field(s, x);
    run_crossed(s, x);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    uint32_t *crossed = malloc((blocks ? blocks : 1) * sizeof *crossed);
    if (!crossed)
        return fc_error_set(err, FC_ERR_NOMEM, "out of memory for the surface's %u block flags", blocks);
    glGetNamedBufferSubData(x->buffers[BIND_CROSSED], 0, (GLsizeiptr)blocks * 4, crossed);
    uint32_t kept = 0;
    for (uint32_t b = 0; b < blocks; b++)
        if (crossed[b])
            g->block_keys[kept++] = g->block_keys[b];
    fc_code code = fc_gl_check("finding the blocks the surface crosses", err);
    if (code == FC_OK && kept < blocks &&
        (uint64_t)blocks * FC_SURFACE_FIELD_BLOCK_BYTES + (uint64_t)kept * FC_SURFACE_BLOCK_BYTES >
            FC_SURFACE_GRID_BUDGET)
        code = fc_error_set(err, FC_ERR_LIMIT,
                            "the surface crosses %u of %u blocks (%llu MiB), past its budget of %llu MiB: raise "
                            "surface_cell",
                            kept, blocks, (unsigned long long)(((uint64_t)kept * FC_SURFACE_BLOCK_BYTES) >> 20),
                            (unsigned long long)(FC_SURFACE_GRID_BUDGET >> 20));
    if (code != FC_OK || kept == blocks) {
        free(crossed);
        return code;
    }
    GLuint all = x->buffers[BIND_FIELD];
    x->buffers[BIND_FIELD] = 0;
    code = make_buffer(&x->buffers[BIND_FIELD], (uint64_t)kept * FC_SURFACE_BLOCK_SAMPLES * 4, NULL, err);
    if (code == FC_OK)
        copy_kept_field(all, x->buffers[BIND_FIELD], crossed, blocks);
    free(crossed);
    glDeleteBuffers(1, &all);
    g->block_count = kept;
    delete_buffer(x, BIND_KEYS);
    delete_buffer(x, BIND_CROSSED);
    if (code == FC_OK)
        code = make_buffer(&x->buffers[BIND_KEYS], (uint64_t)kept * 4, g->block_keys, err);
    return code;
}

static void run_edges(const fc_surface_passes *s, const extraction *x, int emit)
{
    run_program(s, s->edges_program, USES_ISO | USES_EMIT, x, emit);
}

/* One invocation per vertex, in workgroups of 64. */
static void run_vertices(const fc_surface_passes *s, const extraction *x)
{
    GLuint p = s->vertices_program;
    glProgramUniform3fv(p, LOC_ORIGIN, 1, x->grid.origin);
    glProgramUniform1f(p, LOC_CELL, x->grid.cell);
    glProgramUniform1f(p, LOC_ISO, x->iso);
    glProgramUniform1i(p, LOC_KERNEL, x->kernel);
    glProgramUniform1f(p, LOC_BIN, x->grid.bin);
    glProgramUniform3uiv(p, LOC_BINS, 1, x->grid.bins);
    glProgramUniform1i(p, LOC_WITH_ATTRIBUTES, x->with_attributes);
    glProgramUniform1ui(p, LOC_VERTEX_COUNT, x->vertices);
    glUseProgram(p);
    bind_all(x);
    fc_surface_dispatch_blocks(s, (x->vertices + 63u) / 64u);
}

static void run_cells(const fc_surface_passes *s, const extraction *x, int emit)
{
    run_program(s, s->cells_program, USES_ISO | USES_EMIT, x, emit);
}

static uint32_t read_uint(GLuint buffer, uint64_t index)
{
    uint32_t v = 0;
    glGetNamedBufferSubData(buffer, (GLintptr)(index * 4), 4, &v);
    return v;
}

/* The marching cubes tables (surface_cubes.h) as the cells pass reads them: the 256 cases, then the
 * triangles. */
static fc_code upload_cube_tables(extraction *x, fc_error *err)
{
    uint32_t tables[FC_SURFACE_CUBE_CASES + FC_SURFACE_CUBE_TRIANGLES_MAX];
    uint32_t triangles = fc_surface_cube_tables(tables, tables + FC_SURFACE_CUBE_CASES);
    return make_buffer(&x->buffers[BIND_CUBES], (uint64_t)(FC_SURFACE_CUBE_CASES + triangles) * 4, tables, err);
}

/* Field and the crossed blocks, then the counts and their prefix sums: the mesh's size. */
static fc_code count_mesh(const fc_surface_passes *s, extraction *x, fc_error *err)
{
    fc_code code = keep_crossed_blocks(s, x, err);
    if (code == FC_OK)
        code = allocate_scans(x, err);
    if (code == FC_OK)
        code = upload_cube_tables(x, err);
    if (code != FC_OK)
        return code;
    uint64_t blocks = x->grid.block_count;
    run_edges(s, x, 0);
    fc_surface_scan(s, x->buffers[BIND_EDGES], blocks * FC_SURFACE_BLOCK_EDGES);
    run_cells(s, x, 0);
    fc_surface_scan(s, x->buffers[BIND_CELLS], blocks * FC_SURFACE_BLOCK_CELLS);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    x->vertices = read_uint(x->buffers[BIND_EDGES], blocks * FC_SURFACE_BLOCK_EDGES);
    x->triangles = read_uint(x->buffers[BIND_CELLS], blocks * FC_SURFACE_BLOCK_CELLS);
    code = fc_gl_check("counting the surface mesh", err);
    if (code != FC_OK)
        return code;
    uint64_t bytes = (uint64_t)x->vertices * VERTEX_BYTES + (uint64_t)x->triangles * TRIANGLE_BYTES;
    if (bytes + blocks * FC_SURFACE_BLOCK_BYTES > FC_SURFACE_GRID_BUDGET)
        return fc_error_set(err, FC_ERR_LIMIT,
                            "the surface mesh has %u vertices and %u triangles, past its budget of %llu MiB: raise "
                            "surface_cell",
                            x->vertices, x->triangles, (unsigned long long)(FC_SURFACE_GRID_BUDGET >> 20));
    return FC_OK;
}

static fc_code emit_mesh(const fc_surface_passes *s, extraction *x, fc_error *err)
{
    uint64_t v = x->vertices, t = x->triangles;
    fc_code code = make_buffer(&x->buffers[BIND_VERTEX_EDGES], v * 4, NULL, err);
    if (code == FC_OK)
        code = make_buffer(&x->buffers[BIND_POSITIONS], v * 12, NULL, err);
    if (code == FC_OK)
        code = make_buffer(&x->buffers[BIND_NORMALS], v * 12, NULL, err);
    if (code == FC_OK)
        code = make_buffer(&x->buffers[BIND_VERTEX_ATTRIBUTES], v * 16, NULL, err);
    if (code == FC_OK)
        code = make_buffer(&x->buffers[BIND_VERTEX_EXTRAS], v * 8, NULL, err);
    if (code == FC_OK)
        code = make_buffer(&x->buffers[BIND_INDICES], t * 12, NULL, err);
    if (code != FC_OK)
        return code;
    run_edges(s, x, 1);
    run_vertices(s, x);
    run_cells(s, x, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    return fc_gl_check("writing the surface mesh", err);
}

static fc_code allocate_mesh(fc_surface_mesh *m, uint32_t vertices, uint32_t triangles, uint32_t attributes,
                             fc_error *err)
{
    size_t v = vertices, t = triangles;
    m->vertex_count = vertices;
    m->triangle_count = triangles;
    m->attributes = attributes;
    m->positions = malloc(v * 12 + 1);
    m->normals = malloc(v * 12 + 1);
    m->indices = malloc(t * 12 + 1);
    bool ok = m->positions && m->normals && m->indices;
    if (attributes & FC_SURFACE_SPEED)
        ok = ok && (m->speed = malloc(v * 4 + 1));
    if (attributes & FC_SURFACE_DENSITY)
        ok = ok && (m->density = malloc(v * 4 + 1));
    if (attributes & FC_SURFACE_VELOCITY)
        ok = ok && (m->velocity = malloc(v * 12 + 1));
    if (attributes & FC_SURFACE_ID)
        ok = ok && (m->id = malloc(v * 4 + 1));
    return ok ? FC_OK : fc_error_set(err, FC_ERR_NOMEM, "cannot allocate a mesh of %u vertices", vertices);
}

/* Reads the mesh back, the attributes split into their arrays, and checks
 * every index names a vertex (an edge whose owner block is missing would be
 * a bug of the grid, reported rather than passed on). */
static fc_code read_mesh(const extraction *x, fc_surface_mesh *m, fc_error *err)
{
    size_t v = m->vertex_count;
    glGetNamedBufferSubData(x->buffers[BIND_POSITIONS], 0, (GLsizeiptr)(v * 12), m->positions);
    glGetNamedBufferSubData(x->buffers[BIND_NORMALS], 0, (GLsizeiptr)(v * 12), m->normals);
    glGetNamedBufferSubData(x->buffers[BIND_INDICES], 0, (GLsizeiptr)((size_t)m->triangle_count * 12), m->indices);
    float *attributes = malloc(v * 16 + 1);
    uint32_t *extras = malloc(v * 8 + 1);
    if (!attributes || !extras) {
        free(attributes);
        free(extras);
        return fc_error_set(err, FC_ERR_NOMEM, "cannot read back %zu vertices", v);
    }
    glGetNamedBufferSubData(x->buffers[BIND_VERTEX_ATTRIBUTES], 0, (GLsizeiptr)(v * 16), attributes);
    glGetNamedBufferSubData(x->buffers[BIND_VERTEX_EXTRAS], 0, (GLsizeiptr)(v * 8), extras);
    for (size_t i = 0; i < v; i++) {
        if (m->velocity)
            memcpy(m->velocity + 3 * i, attributes + 4 * i, 12);
        if (m->density)
            m->density[i] = attributes[4 * i + 3];
        if (m->speed)
            memcpy(m->speed + i, extras + 2 * i, 4);
        if (m->id)
            m->id[i] = extras[2 * i + 1];
    }
    free(attributes);
    free(extras);
    fc_code code = fc_gl_check("reading the surface mesh back", err);
    for (size_t i = 0; code == FC_OK && i < (size_t)m->triangle_count * 3; i++)
        if (m->indices[i] >= m->vertex_count)
            code = fc_error_set(err, FC_ERR_INTERNAL, "surface mesh triangle %zu names no vertex", i / 3);
    return code;
}

static uint32_t mesh_attributes(const fc_frame *frame)
{
    uint32_t a = 0;
    if (frame->velocity)
        a |= FC_SURFACE_SPEED | FC_SURFACE_VELOCITY;
    if (frame->density)
        a |= FC_SURFACE_DENSITY;
    if (frame->ids)
        a |= FC_SURFACE_ID;
    return a;
}

/* The radius the cell size is measured in, and per-particle radii where each
 * particle keeps its own (fc_radius_source_of). */
static fc_code resolve_radius(const fc_frame *frame, const fc_settings *settings, float *radius,
                              const float **per_particle, fc_error *err)
{
    *per_particle = NULL;
    switch (fc_radius_source_of(settings, frame->radius != NULL)) {
    case FC_RADIUS_FROM_SETTINGS:
        *radius = settings->radius;
        return FC_OK;
    case FC_RADIUS_PER_PARTICLE:
        *per_particle = frame->radius;
        return fc_frame_median_radius(frame, radius, err);
    case FC_RADIUS_ESTIMATED:
        *radius = fc_frame_estimate_radius(frame);
        return FC_OK;
    }
    return fc_error_set(err, FC_ERR_INTERNAL, "unknown radius source");
}

static float largest(const float *values, uint64_t count, float fallback)
{
    if (!values)
        return fallback;
    float m = 0.0f;
    for (uint64_t i = 0; i < count; i++)
        m = fmaxf(m, values[i]);
    return m;
}

static void release(extraction *x)
{
    glDeleteBuffers(BUFFER_COUNT, x->buffers);
    fc_surface_grid_free(&x->grid);
}

/* The ellipsoids' centres packed for the grid, and the longest stretch of any. */
static fc_code ellipsoid_centres(const fc_ellipsoid *ellipsoids, uint64_t count, float **centres, float *stretch,
                                 fc_error *err)
{
    *centres = malloc((size_t)count * 12 + 1);
    if (!*centres)
        return fc_error_set(err, FC_ERR_NOMEM, "cannot allocate %llu ellipsoid centres", (unsigned long long)count);
    *stretch = 1.0f;
    for (uint64_t i = 0; i < count; i++) {
        memcpy(*centres + 3 * i, ellipsoids[i].centre, 12);
        *stretch = fmaxf(*stretch, ellipsoids[i].stretch_max);
    }
    return FC_OK;
}

/* The grid of the frame, its particles uploaded and its blocks' buffers allocated: what the field pass reads. */
static fc_code prepare_grid(const fc_frame *frame, const fc_ellipsoid *ellipsoids, const fc_settings *settings,
                            extraction *x, fc_error *err)
{
    float radius;
    const float *per_particle;
    fc_code code = resolve_radius(frame, settings, &radius, &per_particle, err);
    if (code != FC_OK)
        return code;
    float *centres = NULL, stretch = 1.0f;
    if (settings->surface_kernel != FC_SURFACE_KERNEL_ANISOTROPIC)
        ellipsoids = NULL;
    else if (!ellipsoids)
        return fc_error_set(err, FC_ERR_USAGE, "the anisotropic surface kernel needs the particles' ellipsoids");
    else
        code = ellipsoid_centres(ellipsoids, frame->count, &centres, &stretch, err);
    const float *positions = centres ? centres : frame->positions;
    float reach = fc_surface_kernel_reach_radii(settings->surface_kernel) * stretch *
                  largest(per_particle, frame->count, radius);
    x->iso = iso_of(settings->surface_kernel);
    x->kernel = (int)settings->surface_kernel;
    x->with_attributes = mesh_attributes(frame) != 0;
    if (code == FC_OK)
        code = fc_surface_grid_build(positions, frame->count, reach, settings->surface_cell * radius, &x->grid, err);
    if (code == FC_OK)
        code = upload_particles(x, frame, positions, ellipsoids, per_particle, radius, err);
    free(centres);
    if (code == FC_OK)
        code = allocate_grid(x, err);
    return code;
}

static fc_code extract(const fc_surface_passes *s, const fc_frame *frame, const fc_ellipsoid *ellipsoids,
                       const fc_settings *settings, fc_surface_mesh *out, extraction *x, fc_error *err)
{
    fc_code code = prepare_grid(frame, ellipsoids, settings, x, err);
    if (code == FC_OK)
        code = count_mesh(s, x, err);
    if (code == FC_OK)
        code = emit_mesh(s, x, err);
    if (code == FC_OK)
        code = allocate_mesh(out, x->vertices, x->triangles, mesh_attributes(frame), err);
    if (code == FC_OK)
        code = read_mesh(x, out, err);
    if (code == FC_OK)
        code = fc_surface_smooth(out, settings->surface_smoothing, err);
    return code;
}

fc_code fc_surface_mesher_check(const fc_frame *frame, const fc_settings *settings, fc_error *err)
{
    if (frame->count > FC_SURFACE_MAX_PARTICLES)
        return fc_error_set(err, FC_ERR_LIMIT, "a surface mesh takes at most %u particles, not %llu",
                            FC_SURFACE_MAX_PARTICLES, (unsigned long long)frame->count);
    fc_code code = fc_settings_validate(settings, err);
    return code == FC_OK ? fc_frame_validate(frame, err) : code;
}

fc_code fc_surface_mesher_run(const fc_surface_passes *passes, const fc_frame *frame, const fc_ellipsoid *ellipsoids,
                              const fc_settings *settings, fc_surface_mesh *out, fc_error *err)
{
    memset(out, 0, sizeof *out);
    if (frame->count == 0)
        return FC_OK;
    extraction x = {0};
    fc_code code = extract(passes, frame, ellipsoids, settings, out, &x, err);
    release(&x);
    if (code != FC_OK)
        fc_surface_mesh_free(out);
    return code;
}

fc_code fc_surface_mesher_field(const fc_surface_passes *passes, const fc_frame *frame, const fc_settings *settings,
                                fc_surface_grid *grid, float **field, float *iso, fc_error *err)
{
    memset(grid, 0, sizeof *grid);
    *field = NULL;
    extraction x = {0};
    fc_code code = fc_surface_mesher_check(frame, settings, err);
    if (code == FC_OK && settings->surface_kernel == FC_SURFACE_KERNEL_ANISOTROPIC)
        code = fc_error_set(err, FC_ERR_USAGE, "the field alone is for the isotropic kernels");
    if (code == FC_OK && frame->count > 0)
        code = prepare_grid(frame, NULL, settings, &x, err);
    size_t bytes = (size_t)x.grid.block_count * FC_SURFACE_BLOCK_SAMPLES * 4;
    if (code == FC_OK && !(*field = malloc(bytes + 1)))
        code = fc_error_set(err, FC_ERR_NOMEM, "cannot read back %u blocks' field", x.grid.block_count);
    if (code == FC_OK && bytes) {
        run_field(passes, &x);
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        glGetNamedBufferSubData(x.buffers[BIND_FIELD], 0, (GLsizeiptr)bytes, *field);
        code = fc_gl_check("reading the surface field back", err);
    }
    *iso = x.iso;
    if (code == FC_OK) {
        *grid = x.grid;
        memset(&x.grid, 0, sizeof x.grid);
    } else {
        free(*field);
        *field = NULL;
    }
    release(&x);
    return code;
}
