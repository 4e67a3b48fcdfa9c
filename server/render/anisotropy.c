/* anisotropy.c — the ellipsoids of anisotropy.h by four compute passes: a
 * counting sort of the particles into a uniform grid of cells one support
 * radius wide (count per cell with atomics, prefix sum over the cells,
 * scatter), then one pass per particle over the 27 cells around it. */
#include "anisotropy.h"

#include <math.h>
#include <string.h>

#include "fc_error.h"
#include "gl_util.h"
#include "shader_program.h"

/* Uniform locations fixed by layout(location) in anisotropy_grid.comp.glsl and the passes' shaders. */
enum {
    LOC_PARTICLE_COUNT = 0,
    LOC_GRID_ORIGIN = 1,
    LOC_INVERSE_CELL = 2,
    LOC_GRID_CELLS = 3,
    LOC_SUPPORT = 4,
    LOC_MIN_NEIGHBOURS = 5,
    LOC_LAMBDA = 6,
    LOC_MAX_RATIO = 7
};
enum { LOC_SCAN_COUNT = 0, LOC_SCAN_OFFSET = 8, LOC_SCAN_SUMS = 9, LOC_SCAN_ADD = 10 };
enum { BIND_POSITIONS = 0, BIND_CELL_STARTS = 1, BIND_CELL_RANKS = 2, BIND_SORTED = 3, BIND_ELLIPSOIDS = 4 };
/* local_size of the per-particle passes, and elements one scan workgroup sums (256 lanes x 4). */
enum { PARTICLE_GROUP = 64, SCAN_BLOCK = 1024 };
/* Scan levels: 2^24 cells need three (2^24 / 1024 / 1024 = 16 sums at the top). */
enum { MAX_SCAN_LEVELS = 6 };
/* The grid has at most this many cells per particle (and at least MIN_CELL_CAP, at most MAX_CELL_CAP):
 * particles spread over a box much larger than their own volume (a few far
 * droplets) get cells wider than the support radius instead of unbounded
 * memory. Wider cells stay correct, the search just tests more candidates. */
#define CELLS_PER_PARTICLE 2u
#define MIN_CELL_CAP 4096u
#define MAX_CELL_CAP (1u << 24)
#define CELL_GROWTH 1.25f
/* fc_frame_estimate_radius's radius per nearest-neighbour distance (fc_radius.c). */
#define ESTIMATED_RADIUS_PER_SPACING 0.9f

typedef struct grid {
    float origin[3];
    float cell;
    int32_t cells[3];
    uint32_t total;   /* cells[0] x cells[1] x cells[2] */
} grid;

typedef struct scan_plan {
    int levels;
    uint32_t offset[MAX_SCAN_LEVELS + 1];   /* offset[levels]: the top level's one sum */
    uint32_t count[MAX_SCAN_LEVELS];
} scan_plan;

static fc_code build(const char *dir, const char *file, GLuint *program, fc_error *err)
{
    const char *files[] = {"anisotropy_grid.comp.glsl", file};
    return fc_program_build(dir, files, 2, program, err);
}

fc_code fc_anisotropy_create(const char *shader_dir, fc_anisotropy *a, fc_error *err)
{
    *a = (fc_anisotropy){0};
    const char *scan[] = {"anisotropy_scan.comp.glsl"};
    const char *shape[] = {"anisotropy_grid.comp.glsl", "anisotropy_eigen.glsl", "anisotropy_shape.comp.glsl"};
    fc_code code = build(shader_dir, "anisotropy_count.comp.glsl", &a->count_program, err);
    if (code == FC_OK)
        code = fc_program_build(shader_dir, scan, 1, &a->scan_program, err);
    if (code == FC_OK)
        code = build(shader_dir, "anisotropy_scatter.comp.glsl", &a->scatter_program, err);
    if (code == FC_OK)
        code = fc_program_build(shader_dir, shape, 3, &a->shape_program, err);
    glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, 0, &a->max_groups);
    return code == FC_OK ? fc_gl_check("creating the anisotropy passes", err) : code;
}

static void release_buffers(fc_anisotropy *a)
{
    GLuint buffers[4] = {a->cell_ranks, a->cell_starts, a->sorted, a->ellipsoids};
    glDeleteBuffers(4, buffers);
    a->cell_ranks = a->cell_starts = a->sorted = a->ellipsoids = 0;
    a->particle_capacity = a->cell_capacity = 0;
}

void fc_anisotropy_trim(fc_anisotropy *a)
{
    release_buffers(a);
    a->count = 0;
}

void fc_anisotropy_destroy(fc_anisotropy *a)
{
    release_buffers(a);
    glDeleteProgram(a->count_program);
    glDeleteProgram(a->scan_program);
    glDeleteProgram(a->scatter_program);
    glDeleteProgram(a->shape_program);
    *a = (fc_anisotropy){0};
}

/* Cells one support radius wide over the particles' bounds, wider where
 * that would be more cells than the cap. */
static grid plan_grid(const fc_particle_buffer *pb, float support)
{
    uint64_t cap = (uint64_t)CELLS_PER_PARTICLE * pb->count;
    cap = cap < MIN_CELL_CAP ? MIN_CELL_CAP : cap > MAX_CELL_CAP ? MAX_CELL_CAP : cap;
    grid g = {.cell = support};
    memcpy(g.origin, pb->lo, sizeof g.origin);
    for (;;) {
        uint64_t total = 1;
        for (int k = 0; k < 3; k++) {
            double n = floor((double)(pb->hi[k] - pb->lo[k]) / g.cell) + 1.0;
            g.cells[k] = n < (double)MAX_CELL_CAP ? (int32_t)n : (int32_t)MAX_CELL_CAP;
            total *= (uint64_t)g.cells[k];
        }
        if (total <= cap) {
            g.total = (uint32_t)total;
            return g;
        }
        g.cell *= CELL_GROWTH;
    }
}

/* Where each level of the multi-pass scan lives in the cell buffer: level 0
 * the cells plus one (whose exclusive sum is the particle count, so a cell's
 * end is the next cell's start), each next level one sum per block of the one
 * below. */
static scan_plan plan_scan(uint32_t cells)
{
    scan_plan s = {.levels = 1, .count = {cells + 1}};
    while (s.count[s.levels - 1] > SCAN_BLOCK && s.levels < MAX_SCAN_LEVELS) {
        s.offset[s.levels] = s.offset[s.levels - 1] + s.count[s.levels - 1];
        s.count[s.levels] = (s.count[s.levels - 1] + SCAN_BLOCK - 1) / SCAN_BLOCK;
        s.levels++;
    }
    s.offset[s.levels] = s.offset[s.levels - 1] + s.count[s.levels - 1];
    return s;
}

static fc_code create_buffer(GLsizeiptr bytes, GLuint *buffer, fc_error *err)
{
    glCreateBuffers(1, buffer);
    glNamedBufferStorage(*buffer, bytes > 0 ? bytes : 16, NULL, GL_DYNAMIC_STORAGE_BIT | GL_MAP_READ_BIT);
    return fc_gl_check("allocating the anisotropy buffers", err);
}

/* Grows the buffers (never shrinking) to `particles` and `scan_entries`. */
static fc_code reserve(fc_anisotropy *a, uint64_t particles, uint64_t scan_entries, fc_error *err)
{
    if (a->ellipsoids && particles <= a->particle_capacity && scan_entries <= a->cell_capacity)
        return FC_OK;
    particles = particles > a->particle_capacity ? particles : a->particle_capacity;
    scan_entries = scan_entries > a->cell_capacity ? scan_entries : a->cell_capacity;
    release_buffers(a);
    a->allocations++;
    fc_code code = create_buffer((GLsizeiptr)(particles * 2 * sizeof(uint32_t)), &a->cell_ranks, err);
    if (code == FC_OK)
        code = create_buffer((GLsizeiptr)(scan_entries * sizeof(uint32_t)), &a->cell_starts, err);
    if (code == FC_OK)
        code = create_buffer((GLsizeiptr)(particles * 4 * sizeof(float)), &a->sorted, err);
    if (code == FC_OK)
        code = create_buffer((GLsizeiptr)(particles * sizeof(fc_ellipsoid)), &a->ellipsoids, err);
    if (code != FC_OK) {
        release_buffers(a);
        return code;
    }
    a->particle_capacity = particles;
    a->cell_capacity = scan_entries;
    return FC_OK;
}

/* One invocation per particle, in rows of at most max_groups workgroups. */
static void dispatch_particles(const fc_anisotropy *a, uint64_t count)
{
    uint64_t groups = (count + PARTICLE_GROUP - 1) / PARTICLE_GROUP;
    uint64_t per_row = groups < (uint64_t)a->max_groups ? groups : (uint64_t)a->max_groups;
    glDispatchCompute((GLuint)per_row, (GLuint)((groups + per_row - 1) / per_row), 1);
}

static void set_grid(GLuint program, const grid *g, uint64_t count)
{
    glProgramUniform1ui(program, LOC_PARTICLE_COUNT, (GLuint)count);
    glProgramUniform3fv(program, LOC_GRID_ORIGIN, 1, g->origin);
    glProgramUniform1f(program, LOC_INVERSE_CELL, 1.0f / g->cell);
    glProgramUniform3i(program, LOC_GRID_CELLS, g->cells[0], g->cells[1], g->cells[2]);
}

static void scan_pass(const fc_anisotropy *a, uint32_t offset, uint32_t count, uint32_t sums, bool add)
{
    glProgramUniform1ui(a->scan_program, LOC_SCAN_COUNT, count);
    glProgramUniform1ui(a->scan_program, LOC_SCAN_OFFSET, offset);
    glProgramUniform1ui(a->scan_program, LOC_SCAN_SUMS, sums);
    glProgramUniform1i(a->scan_program, LOC_SCAN_ADD, add);
    glUseProgram(a->scan_program);
    glDispatchCompute((count + SCAN_BLOCK - 1) / SCAN_BLOCK, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

/* Exclusive prefix sum of the cell counts, in place: each level's blocks
 * scanned with their totals written to the level above, the top level in one
 * block, then each level's blocks offset by their scanned totals. */
static void prefix_sum(const fc_anisotropy *a, const scan_plan *s)
{
    for (int k = 0; k < s->levels; k++)
        scan_pass(a, s->offset[k], s->count[k], s->offset[k + 1], false);
    for (int k = s->levels - 2; k >= 0; k--)
        scan_pass(a, s->offset[k], s->count[k], s->offset[k + 1], true);
}

static void bind_buffers(const fc_anisotropy *a, const fc_particle_buffer *particles)
{
    glBindBufferRange(GL_SHADER_STORAGE_BUFFER, BIND_POSITIONS, particles->buffer, 0,
                      (GLsizeiptr)(particles->count * 3 * sizeof(float)));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BIND_CELL_STARTS, a->cell_starts);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BIND_CELL_RANKS, a->cell_ranks);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BIND_SORTED, a->sorted);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BIND_ELLIPSOIDS, a->ellipsoids);
}

static void run_passes(fc_anisotropy *a, const fc_particle_buffer *particles, const grid *g, const scan_plan *s,
                       float support)
{
    const GLuint zero = 0;
    glClearNamedBufferSubData(a->cell_starts, GL_R32UI, 0, (GLsizeiptr)(s->count[0] * sizeof(uint32_t)),
                              GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    bind_buffers(a, particles);
    /* The scatter finds cells through the count's ranks: it has no grid uniforms. */
    set_grid(a->count_program, g, particles->count);
    set_grid(a->shape_program, g, particles->count);
    glProgramUniform1ui(a->scatter_program, LOC_PARTICLE_COUNT, (GLuint)particles->count);
    glUseProgram(a->count_program);
    dispatch_particles(a, particles->count);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    prefix_sum(a, s);
    glUseProgram(a->scatter_program);
    dispatch_particles(a, particles->count);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glProgramUniform1f(a->shape_program, LOC_SUPPORT, support);
    glProgramUniform1ui(a->shape_program, LOC_MIN_NEIGHBOURS, FC_ANISOTROPY_MIN_NEIGHBOURS);
    glProgramUniform1f(a->shape_program, LOC_LAMBDA, FC_ANISOTROPY_LAMBDA);
    glProgramUniform1f(a->shape_program, LOC_MAX_RATIO, FC_ANISOTROPY_MAX_RATIO);
    glUseProgram(a->shape_program);
    dispatch_particles(a, particles->count);
    /* The splats read the ellipsoids from storage buffers; the readback of tests through a copy. */
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

float fc_anisotropy_support(float estimated_radius)
{
    return FC_ANISOTROPY_SUPPORT_SPACINGS * estimated_radius / ESTIMATED_RADIUS_PER_SPACING;
}

fc_code fc_anisotropy_update(fc_anisotropy *a, const fc_particle_buffer *particles, float support, fc_error *err)
{
    if (a->ellipsoids && a->generation == particles->generation && a->count == particles->count)
        return FC_OK;
    grid g = plan_grid(particles, support);
    scan_plan s = plan_scan(g.total);
    fc_code code = reserve(a, particles->count, (uint64_t)s.offset[s.levels] + 1, err);
    if (code != FC_OK)
        return code;
    if (particles->count > 0)
        run_passes(a, particles, &g, &s, support);
    code = fc_gl_check("anisotropy passes", err);
    if (code == FC_OK) {
        a->computations++;
        a->generation = particles->generation;
        a->count = particles->count;
        a->support = support;
        a->cells = g.total;
    }
    return code;
}

fc_code fc_anisotropy_read(const fc_anisotropy *a, uint64_t count, fc_ellipsoid *out, fc_error *err)
{
    if (count > a->count)
        return fc_error_set(err, FC_ERR_USAGE, "fc_anisotropy_read: %llu ellipsoids asked, %llu computed",
                            (unsigned long long)count, (unsigned long long)a->count);
    if (count > 0)
        glGetNamedBufferSubData(a->ellipsoids, 0, (GLsizeiptr)(count * sizeof *out), out);
    return fc_gl_check("reading the ellipsoids back", err);
}

float fc_anisotropy_reach(const fc_particle_buffer *particles, float radius)
{
    float largest = fc_particle_buffer_largest_radius(particles, radius);
    return particles->shapes ? largest * FC_ANISOTROPY_MAX_STRETCH : largest;
}

void fc_anisotropy_tally(const fc_anisotropy *a, fc_gpu_memory *m)
{
    m->particle_bytes += a->particle_capacity * (2 * sizeof(uint32_t) + 4 * sizeof(float) + sizeof(fc_ellipsoid));
    m->particle_bytes += a->cell_capacity * sizeof(uint32_t);
    m->allocations += a->allocations;
}
