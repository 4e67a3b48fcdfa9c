/* surface_grid.h — the sparse grid a surface mesh is extracted on
 * (surface_extract.h): blocks of FC_SURFACE_BLOCK^3 cells, only those near
 * particles, each octant of a block with the list of the particles whose
 * field reaches its samples (Janisz's "particle lookup cache" per block,
 * after Rosenberg & Birdwell 2008; octants, not whole blocks, so that a sample
 * tests a few times the particles that reach it rather than dozens of times).
 * Built on the CPU by stable radix sorts of (block, particle) and (octant,
 * particle) pairs, so that equal input gives equal lists in particle order.
 *
 * A block holds (FC_SURFACE_BLOCK + 1)^3 samples: its cells' corners, the
 * upper faces included. Neighbouring blocks so evaluate the same lattice
 * points with the same arithmetic and agree on them bit for bit, which is
 * what makes cracks between blocks impossible. */
#ifndef FC_SURFACE_GRID_H
#define FC_SURFACE_GRID_H

#include <stdint.h>

#include "fluidcast_types.h"

#define FC_SURFACE_BLOCK 8u                       /* cells per block edge */
#define FC_SURFACE_BLOCK_SAMPLES 729u             /* (FC_SURFACE_BLOCK + 1)^3 */
#define FC_SURFACE_BLOCK_CELLS 512u               /* FC_SURFACE_BLOCK^3 */
#define FC_SURFACE_BLOCK_EDGES 3584u              /* 7 lattice edges per cell corner it owns */
#define FC_SURFACE_KEY_BITS 10u                   /* bits of a block coordinate in a key */
/* A block's samples split in two halves per axis: samples [0, HALF) and
 * [HALF, FC_SURFACE_BLOCK] (the upper face with the upper half). */
#define FC_SURFACE_HALF 4u
#define FC_SURFACE_OCTANTS 8u
#define FC_SURFACE_MAX_BLOCKS_PER_AXIS (1u << FC_SURFACE_KEY_BITS)
/* The most particles one extraction takes (their lists are indexed by 32 bits). */
#define FC_SURFACE_MAX_PARTICLES (1u << 28)
/* GPU and CPU bytes one extraction may use for its grid (samples, edges,
 * cells, lists): past it the request fails with LIMIT instead of exhausting
 * the machine. */
#define FC_SURFACE_GRID_BUDGET ((uint64_t)1 << 30)
/* Bytes a block costs on the GPU: per sample its field and gradient (vec4),
 * velocity and density (vec4), speed and nearest id; per owned edge
 * (7 per cell) and per cell a scan entry. */
#define FC_SURFACE_BLOCK_BYTES ((uint64_t)FC_SURFACE_BLOCK_SAMPLES * 40u + (uint64_t)FC_SURFACE_BLOCK_EDGES * 4u + (uint64_t)FC_SURFACE_BLOCK_CELLS * 4u)

typedef struct fc_surface_grid {
    float origin[3];          /* world position of lattice point (0, 0, 0) */
    float cell;               /* cell edge, world units */
    uint32_t block_count;
    uint32_t *block_keys;     /* ascending: x | y << 10 | z << 20, block coordinates */
    uint32_t *list_starts;    /* 8 block_count + 1: octant o (x | y << 1 | z << 2, the upper halves) of block b
                                 reads list[list_starts[8 b + o] .. [8 b + o + 1]) */
    uint32_t *list;           /* particle indices, ascending within an octant */
} fc_surface_grid;

/* Builds the grid of cells `cell` wide around `count` particles (xyz
 * interleaved, finite) each of whose field reaches at most `reach` from its
 * centre. LIMIT when the frame spans more than FC_SURFACE_MAX_BLOCKS_PER_AXIS
 * blocks along an axis or the grid would pass FC_SURFACE_GRID_BUDGET;
 * NOMEM when memory runs out. On failure the grid is empty. */
fc_code fc_surface_grid_build(const float *positions, uint64_t count, float reach, float cell,
                              fc_surface_grid *out, fc_error *err);

void fc_surface_grid_free(fc_surface_grid *grid);

#endif
