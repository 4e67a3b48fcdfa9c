/* spray_classes.h — which particles are spray (Ihmsen et al. 2012, "Unified
 * spray, foam and air bubbles for particle-based fluids", §3: a particle's
 * class follows from how many neighbours it has): a particle with fewer
 * than `spray_neighbours` others within the anisotropy's support radius
 * (FC_ANISOTROPY_SUPPORT_SPACINGS of the frame's own spacing, so the same
 * neighbourhood whatever the render radius) is an isolated droplet, drawn by
 * the spray pass instead of joining the surface. A jet or a thin sheet keeps
 * its neighbours along it (a row of particles has 4 within 2.2 spacings, 2
 * at its ends) and stays surface at the default of 2.
 *
 * The classes reach the pipeline as the sort keys of the density order
 * (density_order.h): a spray particle's key is 0, any other's its density
 * (at least FLT_MIN; FLT_MAX without densities, which no density threshold
 * applies to), so every density threshold and
 * the neighbour classes split surface from spray at one prefix of one
 * order. Counted on the CPU over a grid of cells one support wide, kept in a
 * table whose slot is a cell's coordinates modulo a power of two per axis
 * (no two cells of the frame's box share one unless the box is far larger
 * than the fluid), with the positions gathered in slot order, so a cell and
 * its neighbours are read from a few runs of memory; a particle stops
 * counting at `spray_neighbours`, so the cost is about one pass over the
 * particles and their nearest few neighbours, cut into ranges of slots on
 * the usable cores (fc_parallel.h). */
#ifndef FC_SPRAY_CLASSES_H
#define FC_SPRAY_CLASSES_H

#include <float.h>
#include <stdint.h>

#include "fc_frame.h"
#include "fluidcast_types.h"

typedef struct fc_spray_classes {
    float *keys;            /* per particle, frame order: the density order's sort key */
    uint32_t *cell_start;   /* slot -> first entry in `sorted`, cells + 1 entries */
    uint32_t *sorted;       /* particle indices grouped by slot */
    float *gathered;        /* their positions in the same order, 3 floats an entry */
    uint32_t *slot_of;      /* per particle, frame order: its cell's slot */
    uint64_t capacity;      /* particles the arrays hold */
    uint64_t cell_capacity;
    uint64_t cells;         /* slots of the last grid (a power of two); 0 when none was built */
    float support;          /* the neighbourhood's radius the grid's cells are wide, world units */
    float lo[3];            /* the frame's box minimum: cell (0,0,0) starts here */
    uint32_t bits[3];       /* slot bits per axis (at least 2) */
} fc_spray_classes;

/* The smallest density threshold that splits off the neighbour classes'
 * spray (key 0) when no density threshold is asked for. */
#define FC_SPRAY_KEY_THRESHOLD FLT_MIN

/* Fills c->keys for `frame`: 0 for the particles with fewer than
 * `spray_neighbours` neighbours within `support` (the anisotropy's support
 * radius of the frame's spacing, fc_anisotropy_support; none when 0 or not
 * positive, or when they would be most of the frame), else the particle's
 * density (or FLT_MAX). FC_ERR_NOMEM when the arrays cannot grow. */
fc_code fc_spray_classes_compute(fc_spray_classes *c, const fc_frame *frame, float support,
                                 uint32_t spray_neighbours, fc_error *err);

/* The threshold of the density order that makes the spray of `settings`:
 * its density threshold, or FC_SPRAY_KEY_THRESHOLD for the neighbour classes
 * alone, 0 when neither asks for spray. */
float fc_spray_classes_threshold(const fc_settings *settings);

/* The slots of the last grid a neighbourhood of position p lies in (the
 * cell holding p and the 26 around it, 27 different slots), the one holding
 * p first, for passes that walk the same neighbourhoods (foam_classes.h);
 * returns 27. c->cells must be > 0. */
uint32_t fc_spray_classes_cells_around(const fc_spray_classes *c, const float *p, uint32_t cells[27]);

void fc_spray_classes_free(fc_spray_classes *c);

#endif
