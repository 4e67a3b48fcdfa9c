/* reader_hdf5_table.h — internal to the HDF5 reader: one group of particle
 * datasets read into doubles by what each dataset means (positions, velocity,
 * density, smoothing length, ids, other per-particle scalars), with every
 * dataset checked for its class, rank, shape and size before it is read, and
 * libhdf5's failures turned into messages. */
#ifndef FC_READER_HDF5_TABLE_H
#define FC_READER_HDF5_TABLE_H

#include <hdf5.h>
#include <stdbool.h>
#include <stdint.h>
#include "fluidcast_types.h"

enum { H5_MAX_EXTRAS = 32, H5_NAME_MAX = 64 };

/* One particle group's values. Arrays are malloc'd, NULL when the group lacks them. */
typedef struct h5_table {
    uint64_t count;
    double *position;   /* 3 count, x y z interleaved */
    double *velocity;   /* 3 count */
    double *density;
    double *radius;     /* the smoothing length h */
    double *ids;
    size_t extra_count; /* other numeric 1-D datasets of count values, by name */
    char extra_names[H5_MAX_EXTRAS][H5_NAME_MAX];
    double *extras[H5_MAX_EXTRAS];
    bool no_positions;  /* why h5_table_read_group failed: the group has no positions at all */
    size_t position_value_size; /* bytes of the widest position dataset's values: 8 for float64 */
} h5_table;

/* What the reader shares with the table functions: the file's name for messages
 * and its size, which bounds how many values a dataset may claim. */
typedef struct h5_source {
    const char *name;
    size_t size;
} h5_source;

/* Reads the datasets of the group `path` (opened as `group`) into *t (zeroed first).
 * Positions are required: Coordinates (N x 3, SWIFT/GADGET) or x, y, z; velocity is
 * Velocities or vx vy vz or u v w; density Density or rho; the smoothing length
 * SmoothingLength or h; ids ParticleIDs or id. Names match case-insensitively. */
fc_code h5_table_read_group(const h5_source *s, hid_t group, const char *path, h5_table *t, fc_error *err);

/* Positions only, from one N x 3 dataset or three 1-D datasets of N values (paths from the root). */
fc_code h5_table_read_positions(const h5_source *s, hid_t file, const char *const *paths, size_t path_count,
                                h5_table *t, fc_error *err);

void h5_table_free(h5_table *t);

/* FC_ERR_PARSE "<name>: <what>: <libhdf5's innermost reason>" (the error stack is cleared). */
fc_code h5_fail(const h5_source *s, fc_error *err, const char *what);

#endif
