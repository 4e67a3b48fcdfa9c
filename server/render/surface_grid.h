/* surface_grid.h — the sparse grid a surface mesh is extracted on
 * (surface_extract.h): blocks of FC_SURFACE_BLOCK^3 cells, only those near
 * particles, and the particles sorted into bins at least the field's reach
 * wide (Janisz's "particle lookup cache", after Rosenberg & Birdwell 2008):
 * a sample sums the particles of the bins within FC_SURFACE_BIN_SPLIT of its own, so every
 * particle is listed once whatever the cell size, and a sample tests a few
 * dozen particles rather than all those of a block. Built on the CPU: the
 * blocks by marking those each particle reaches in a bitmap, the bins by a
 * stable counting sort, so that equal input gives equal bins in particle order.
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
#define FC_SURFACE_EDGE_DIRECTIONS 3u             /* lattice edges per point: x, y, z (marching cubes) */
#define FC_SURFACE_BLOCK_EDGES 1536u              /* FC_SURFACE_EDGE_DIRECTIONS per cell corner it owns */
#define FC_SURFACE_KEY_BITS 10u                   /* bits of a block coordinate in a key */
#define FC_SURFACE_MAX_BLOCKS_PER_AXIS (1u << FC_SURFACE_KEY_BITS)
/* The most particles one extraction takes (their lists are indexed by 32 bits). */
#define FC_SURFACE_MAX_PARTICLES (1u << 28)
/* Bins per field reach: a sample reads the (2 SPLIT + 1)^3 bins around its
 * own. 2 tests about 15 r^3 of particles per sample where 1 tests 27 r^3. */
#define FC_SURFACE_BIN_SPLIT 2u
/* The most bins of the particles' box (their starts take 4 bytes each). */
#define FC_SURFACE_MAX_BINS (1u << 24)
/* GPU and CPU bytes one extraction may use for its grid (samples, edges,
 * cells, bins): past it the request fails with LIMIT instead of exhausting
 * the machine. */
#define FC_SURFACE_GRID_BUDGET ((uint64_t)1 << 30)
/* Bytes every block of the grid costs on the GPU: per sample its field's
 * value, and whether the surface crosses it (surface_crossed.comp.glsl). */
#define FC_SURFACE_FIELD_BLOCK_BYTES ((uint64_t)FC_SURFACE_BLOCK_SAMPLES * 4u + 4u)
/* Bytes a block the surface crosses costs besides: its field once more (the
 * crossed blocks' own copy), per owned edge (3 per cell) and per cell a scan
 * entry. */
#define FC_SURFACE_BLOCK_BYTES ((uint64_t)FC_SURFACE_BLOCK_SAMPLES * 4u + (uint64_t)FC_SURFACE_BLOCK_EDGES * 4u + (uint64_t)FC_SURFACE_BLOCK_CELLS * 4u)

typedef struct fc_surface_grid {
    float origin[3];          /* world position of lattice point (0, 0, 0) */
    float cell;               /* cell edge, world units */
    uint32_t block_count;
    uint32_t *block_keys;     /* ascending: x | y << 10 | z << 20, block coordinates */
    float bin;                /* bin edge, world units, the field's reach / FC_SURFACE_BIN_SPLIT or more; bin
                                 (0, 0, 0) starts at origin */
    uint32_t bins[3];         /* bins along each axis */
    uint32_t *bin_starts;     /* bins[0] bins[1] bins[2] + 1: bin x + bins[0] (y + bins[1] z) holds the
                                 particles order[bin_starts[i] .. bin_starts[i + 1]) */
    uint32_t *order;          /* the particle indices by bin, ascending within a bin */
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
