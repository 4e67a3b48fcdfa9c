/* fc_frame.h — allocating, validating and measuring particle frames; the camera's defaults. */
#ifndef FC_FRAME_H
#define FC_FRAME_H

#include <stdbool.h>
#include "fc_api.h"
#include "fluidcast_types.h"
#include "fc_settings.h"   /* fc_settings_default, fc_settings_validate: the settings' table */

#ifdef __cplusplus
extern "C" {
#endif

/* Attribute bits, as carried in FRAME's attribute mask (PROTOCOL.md). */
enum {
    FC_ATTR_DENSITY = 1u << 0,
    FC_ATTR_VELOCITY = 1u << 1,
    FC_ATTR_IDS = 1u << 2,
    FC_ATTR_RADIUS = 1u << 3
};

/* Every attribute bit this version knows. */
#define FC_ATTR_ALL (FC_ATTR_DENSITY | FC_ATTR_VELOCITY | FC_ATTR_IDS | FC_ATTR_RADIUS)

/* The largest per-particle radius a frame may carry, as the radius setting
 * (PROTOCOL.md 7.3, 7.5): beyond it a splat covers no useful picture. */
#define FC_FRAME_MAX_RADIUS 1e6f

/* Allocates the arrays of a frame of `count` particles: positions always, the
 * others when their bit is in `attributes`. Contents are uninitialised.
 * Guards count*stride against overflow. FC_ERR_USAGE for count 0 or unknown
 * attribute bits, FC_ERR_NOMEM when memory runs out; on failure the frame is
 * left empty. */
FC_API fc_code fc_frame_alloc(fc_frame *frame, uint64_t count, uint32_t attributes, fc_error *err);

/* Bytes per particle of the arrays an attribute mask asks for: 12 (positions)
 * to 36; FRAME's S (PROTOCOL.md 7.3). Unknown bits add nothing. */
FC_API size_t fc_frame_particle_bytes(uint32_t attributes);

/* Bytes of one block that holds all of a frame's arrays back to back, in
 * FRAME's order (positions, density, velocity, ids, radius); 0 when that would not
 * fit size_t. */
FC_API size_t fc_frame_block_size(uint64_t count, uint32_t attributes);

/* Points the frame's arrays into such a block (4-byte aligned, at least
 * fc_frame_block_size bytes). The frame does not own the block: never
 * fc_frame_free it. */
FC_API void fc_frame_point_into_block(fc_frame *frame, uint8_t *block, uint64_t count, uint32_t attributes);

/* Frees every array and zeroes the frame. Safe on a zeroed frame. */
FC_API void fc_frame_free(fc_frame *frame);

/* Attribute mask of the arrays present. */
FC_API uint32_t fc_frame_attributes(const fc_frame *frame);

/* Checks every position (and velocity/density when present) is finite, and
 * every radius (when present) finite, > 0 and <= FC_FRAME_MAX_RADIUS.
 * FC_ERR_INVALID_VALUE naming the first offending particle otherwise. */
FC_API fc_code fc_frame_validate(const fc_frame *frame, fc_error *err);

/* The median of the frame's per-particle radii (the upper median for an even
 * count), found in O(count) on a copy; 0 when the frame has no radii.
 * FC_ERR_NOMEM when the copy cannot be made. Radii must be valid
 * (fc_frame_validate). */
FC_API fc_code fc_frame_median_radius(const fc_frame *frame, float *median, fc_error *err);

/* Axis-aligned bounds of the positions. count must be > 0. */
FC_API void fc_frame_bounds(const fc_frame *frame, float lo[3], float hi[3]);

/* Estimates a sphere radius that closes the surface: 0.9 x the median
 * nearest-neighbour distance of (a deterministic sample of at most 4096)
 * particles, the neighbour being the nearest particle at a different position
 * among all particles, found exactly with a grid in O(count). Positions must be
 * finite (fc_frame_validate). Always positive: a frame whose particles all
 * coincide (or count <= 1) gets 1.0; never more than 1e6, the largest radius
 * settings accept. */
FC_API float fc_frame_estimate_radius(const fc_frame *frame);

/* A camera that frames the frame's bounding box: it looks at the box centre
 * along the direction (-1, 1.4, -0.9) (from the +x,-y,+z side), up = +z, vertical
 * fov 40 degrees, far enough that the box's bounding sphere fits the smaller of the
 * two fields of view. */
FC_API void fc_camera_frame_bounds(const fc_frame *frame, uint32_t width, uint32_t height, fc_camera *cam);

/* Checks a camera: finite vectors, eye != target, up not parallel to the view
 * direction, fov in (0,180), width/height >= 1. */
FC_API fc_code fc_camera_validate(const fc_camera *cam, fc_error *err);

#ifdef __cplusplus
}
#endif
#endif
