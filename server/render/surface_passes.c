/* surface_passes.c — building the surface passes' programs, dispatching them
 * over blocks, and the multi-level prefix sum (as anisotropy.c runs it). */
#include "surface_passes.h"

#include <stdio.h>
#include <string.h>

#include "gl_util.h"
#include "shader_program.h"
#include "surface_cubes.h"
#include "surface_grid.h"
#include "surface_mesher.h"

/* Uniform locations of anisotropy_scan.comp.glsl. */
enum { LOC_SCAN_COUNT = 0, LOC_SCAN_OFFSET = 8, LOC_SCAN_SUMS = 9, LOC_SCAN_ADD = 10 };
enum { BIND_SCAN = 1, SCAN_BLOCK = 1024, MAX_SCAN_LEVELS = 6 };

typedef struct scan_plan {
    int levels;
    uint64_t offset[MAX_SCAN_LEVELS + 1];
    uint64_t count[MAX_SCAN_LEVELS];
} scan_plan;

/* Level 0 the values plus one (whose exclusive sum is the total), each next
 * level one sum per block of the one below. */
static scan_plan plan_scan(uint64_t n)
{
    scan_plan s = {.levels = 1, .count = {n + 1}};
    while (s.count[s.levels - 1] > SCAN_BLOCK && s.levels < MAX_SCAN_LEVELS) {
        s.offset[s.levels] = s.offset[s.levels - 1] + s.count[s.levels - 1];
        s.count[s.levels] = (s.count[s.levels - 1] + SCAN_BLOCK - 1) / SCAN_BLOCK;
        s.levels++;
    }
    s.offset[s.levels] = s.offset[s.levels - 1] + s.count[s.levels - 1];
    return s;
}

uint64_t fc_surface_scan_entries(uint64_t n)
{
    scan_plan s = plan_scan(n);
    return s.offset[s.levels] + 1;
}

static void scan_pass(const fc_surface_passes *s, uint64_t offset, uint64_t count, uint64_t sums, int add)
{
    glProgramUniform1ui(s->scan_program, LOC_SCAN_COUNT, (GLuint)count);
    glProgramUniform1ui(s->scan_program, LOC_SCAN_OFFSET, (GLuint)offset);
    glProgramUniform1ui(s->scan_program, LOC_SCAN_SUMS, (GLuint)sums);
    glProgramUniform1i(s->scan_program, LOC_SCAN_ADD, add);
    glUseProgram(s->scan_program);
    uint64_t groups = (count + SCAN_BLOCK - 1) / SCAN_BLOCK;
    glDispatchCompute((GLuint)groups, 1, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
}

void fc_surface_scan(const fc_surface_passes *s, GLuint buffer, uint64_t n)
{
    scan_plan p = plan_scan(n);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BIND_SCAN, buffer);
    for (int k = 0; k < p.levels; k++)
        scan_pass(s, p.offset[k], p.count[k], p.offset[k + 1], 0);
    for (int k = p.levels - 2; k >= 0; k--)
        scan_pass(s, p.offset[k], p.count[k], p.offset[k + 1], 1);
}

void fc_surface_dispatch_blocks(const fc_surface_passes *s, uint32_t blocks)
{
    uint32_t per_row = blocks < (uint32_t)s->max_groups ? blocks : (uint32_t)s->max_groups;
    if (per_row == 0)
        return;
    glDispatchCompute(per_row, (blocks + per_row - 1) / per_row, 1);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

/* The grid's sizes as the shaders' #defines, from surface_grid.h. */
static void grid_defines(char *out, size_t size)
{
    snprintf(out, size,
             "#define FC_SURFACE_GRID 1\n#define BLOCK %uu\n#define BLOCK_SAMPLES %uu\n#define BLOCK_CELLS %uu\n#define EDGE_DIRECTIONS %uu\n"
             "#define BLOCK_EDGES %uu\n#define KEY_BITS %uu\n#define MISSING 0xFFFFFFFFu\n"
             "#define METABALL_REACH_RADII %.9f\n#define SPH_REACH_RADII %.9f\n#define BIN_SPLIT %uu\n#define CUBE_CASES %uu\n",
             FC_SURFACE_BLOCK, FC_SURFACE_BLOCK_SAMPLES, FC_SURFACE_BLOCK_CELLS, FC_SURFACE_EDGE_DIRECTIONS, FC_SURFACE_BLOCK_EDGES,
             FC_SURFACE_KEY_BITS, (double)FC_SURFACE_METABALL_REACH_RADII, (double)FC_SURFACE_SPH_REACH_RADII,
             FC_SURFACE_BIN_SPLIT, FC_SURFACE_CUBE_CASES);
}

fc_code fc_surface_passes_create(const char *shader_dir, fc_surface_passes *s, fc_error *err)
{
    memset(s, 0, sizeof *s);
    char defines[384];
    grid_defines(defines, sizeof defines);
    const char *field[] = {"surface_grid.comp.glsl", "surface_kernel.comp.glsl", "surface_field.comp.glsl"};
    const char *crossed[] = {"surface_grid.comp.glsl", "surface_crossed.comp.glsl"};
    const char *edges[] = {"surface_grid.comp.glsl", "surface_edges.comp.glsl"};
    const char *vertices[] = {"surface_grid.comp.glsl", "surface_kernel.comp.glsl", "surface_vertices.comp.glsl"};
    const char *cells[] = {"surface_grid.comp.glsl", "surface_cells.comp.glsl"};
    const char *scan[] = {"anisotropy_scan.comp.glsl"};
    fc_code code = fc_program_build_defines(shader_dir, defines, field, 3, &s->field_program, err);
    if (code == FC_OK)
        code = fc_program_build_defines(shader_dir, defines, crossed, 2, &s->crossed_program, err);
    if (code == FC_OK)
        code = fc_program_build_defines(shader_dir, defines, edges, 2, &s->edges_program, err);
    if (code == FC_OK)
        code = fc_program_build_defines(shader_dir, defines, cells, 2, &s->cells_program, err);
    if (code == FC_OK)
        code = fc_program_build_defines(shader_dir, defines, vertices, 3, &s->vertices_program, err);
    if (code == FC_OK)
        code = fc_program_build(shader_dir, scan, 1, &s->scan_program, err);
    if (code != FC_OK) {
        fc_surface_passes_destroy(s);
        return code;
    }
    glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, 0, &s->max_groups);
    return fc_gl_check("building the surface mesh passes", err);
}

void fc_surface_passes_destroy(fc_surface_passes *s)
{
    glDeleteProgram(s->field_program);
    glDeleteProgram(s->crossed_program);
    glDeleteProgram(s->edges_program);
    glDeleteProgram(s->cells_program);
    glDeleteProgram(s->vertices_program);
    glDeleteProgram(s->scan_program);
    memset(s, 0, sizeof *s);
}
