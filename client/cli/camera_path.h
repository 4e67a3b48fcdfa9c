/* camera_path.h — the camera keyframe file of `fluidcast render
 * --camera-path FILE.json`: a JSON array of keyframes, or an object whose
 * "keyframes" member is that array, each
 *
 *     { "frame": 12, "eye": [x, y, z], "target": [x, y, z],
 *       "up": [x, y, z], "fov": 35 }
 *
 * "frame" is a frame number of the sequence (the number in the file names of
 * a %d or {} pattern, else the position 0, 1, ... in the list), strictly
 * increasing from keyframe to keyframe; "eye" and "target" are required; "up"
 * (default: the sequence's up) and "fov" (vertical, degrees, default: --fov)
 * may be left out. No other member is allowed, so that a misspelt one is an
 * error rather than ignored.
 *
 * Between keyframes the eye and the target follow a Catmull-Rom spline
 * parameterised by frame number (the tangent at a keyframe is the chord
 * between its two neighbours over their frame distance; at the first and last
 * keyframe the chord to its one neighbour), so the camera passes through every
 * keyframe with a continuous velocity, and two keyframes move it along a
 * straight line at constant speed. Up and fov are interpolated linearly. Before
 * the first keyframe and after the last the camera holds still.
 *
 * This file depends on the protocol library and cJSON only, so that the fuzz
 * targets build it. */
#ifndef FC_CAMERA_PATH_H
#define FC_CAMERA_PATH_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "fluidcast_types.h"

#define FC_CAMERA_PATH_MAX_BYTES (16u << 20)
#define FC_CAMERA_PATH_MAX_KEYS 100000u

/* The values are the floats fc_camera carries, converted from the file's
 * numbers before they are checked: a number that is finite or below 180 as a
 * double but not as a float (1e39, 179.99999999995) is refused here rather
 * than sent to the daemon, which would refuse the render. */
typedef struct fc_camera_key {
    uint32_t frame;
    float eye[3], target[3], up[3];
    float fov_deg;
    bool has_up, has_fov;
} fc_camera_key;

typedef struct fc_camera_path {
    fc_camera_key *keys;    /* count of them, by increasing frame */
    uint32_t count;         /* >= 1 */
} fc_camera_path;

/* Parses `size` bytes of JSON; `name` (the file's) starts every message.
 * FC_ERR_PARSE for text that is not JSON (naming the line and column), for a
 * structure other than the above (naming the keyframe, its frame and the
 * member: missing, of the wrong type, unknown, given twice, a number that is
 * not finite as a float, a fov outside (0, 180) as a float, an eye equal to its
 * target as floats, frames that do not increase) and for
 * no keyframe; FC_ERR_LIMIT for more than FC_CAMERA_PATH_MAX_KEYS keyframes
 * or FC_CAMERA_PATH_MAX_BYTES bytes; FC_ERR_NOMEM. Free with fc_camera_path_free. */
fc_code fc_camera_path_parse(const char *text, size_t size, const char *name, fc_camera_path *out, fc_error *err);

/* Reads (fc_read_file) and parses the file. FC_ERR_IO naming it when it cannot
 * be read, FC_ERR_TOO_LARGE when it holds more than FC_CAMERA_PATH_MAX_BYTES. */
fc_code fc_camera_path_load(const char *path, fc_camera_path *out, fc_error *err);

void fc_camera_path_free(fc_camera_path *p);

/* The camera at frame number `frame`: `base` gives the image size, and the up
 * and fov of keyframes without them. */
void fc_camera_path_at(const fc_camera_path *p, uint32_t frame, const fc_camera *base, fc_camera *out);

#endif
