/* reader_fields.h — internal to the particle readers: the per-particle values a
 * file can provide, how columns/properties are named, and storing a parsed
 * value into a frame with the checks every format shares. */
#ifndef FC_READER_FIELDS_H
#define FC_READER_FIELDS_H

#include <stdbool.h>
#include "fluidcast_types.h"
#include "reader_cursor.h"

/* X..Z and VX..VZ are contiguous so a 3-component array maps to first + k. */
typedef enum fc_field {
    FC_FIELD_NONE = 0,
    FC_FIELD_X,
    FC_FIELD_Y,
    FC_FIELD_Z,
    FC_FIELD_DENSITY,
    FC_FIELD_VX,
    FC_FIELD_VY,
    FC_FIELD_VZ,
    FC_FIELD_ID,
    FC_FIELD_RADIUS,   /* per-particle splat radius (FRAME attribute bit 3): radius, pscale */
    FC_FIELD_COUNT
} fc_field;

/* The field a PLY property or CSV column denotes (x y z density|rho vx vy vz id
 * radius|pscale, case-insensitive); FC_FIELD_NONE for any other name. */
fc_field fc_field_from_name(fc_span name);
const char *fc_field_name(fc_field field);

/* The fields found in a file's header. */
typedef struct fc_field_set {
    bool present[FC_FIELD_COUNT];
} fc_field_set;

/* Marks field present; false when it already was (a duplicate column). */
bool fc_field_set_add(fc_field_set *set, fc_field field);
/* The fc_frame_alloc attribute mask for the set; false when x, y, z are not all
 * present or velocity is incomplete, with *missing naming what is lacking. */
bool fc_field_set_attributes(const fc_field_set *set, uint32_t *attributes, const char **missing);

/* Allocates frame for count particles; FC_ERR_PARSE "no particles" for 0,
 * allocation failures keep their code with the file named. */
fc_code fc_reader_alloc_frame(const fc_cursor *c, fc_frame *frame, uint64_t count,
                              uint32_t attributes, fc_error *err);

/* Stores value as field of particle index; false when it does not fit the field:
 * non-finite or beyond float range, an id that is not an integer in 0..UINT32_MAX,
 * or a radius outside (0, 1e6] (PROTOCOL.md 7.3). */
bool fc_field_store(fc_frame *frame, uint64_t index, fc_field field, double value);
/* Float64 positions in double until particle_reader.c has chosen the recentring. */
typedef struct fc_positions64 {
    double *xyz;        /* 3 x count, allocated by the first store */
    uint64_t count;
    bool out_of_memory;
} fc_positions64;

/* For a position component (FC_FIELD_X..Z) read from a float64 value: keeps it in c's
 * positions64 when the read recentres, else stores it like fc_field_store. False when not
 * finite (or, unstaged, beyond float range) or out of memory. */
bool fc_field_store_position64(const fc_cursor *c, fc_frame *frame, uint64_t index, fc_field field, double value);

/* What fc_field_store requires of a value of field, for messages ("a finite value in float range"). */
const char *fc_field_requirement(fc_field field);
/* FC_ERR_PARSE at c's position explaining why fc_field_store refused value. */
fc_code fc_field_reject(const fc_cursor *c, fc_error *err, uint64_t index, fc_field field, double value);

#endif
