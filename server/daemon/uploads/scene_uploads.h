/* scene_uploads.h — the scene images a client sent (BACKGROUND, ENVIRONMENT),
 * decoded on the event loop when they arrive and shared by reference with the
 * render jobs that use them, like frames (shared_frame.h). The GL thread turns
 * them into textures (scene_texture_cache.h). */
#ifndef FC_DAEMON_SCENE_UPLOADS_H
#define FC_DAEMON_SCENE_UPLOADS_H

#include <stdatomic.h>
#include <stddef.h>
#include <stdint.h>

#include "image.h"
#include "wire_scene.h"

/* One decoded background (1 image) or cube map (6 faces, +X -X +Y -Y +Z -Z).
 * Immutable once created; freed with its last reference, from any thread. */
typedef struct fc_scene_part {
    atomic_uint refs;
    uint32_t count;
    fc_image images[FC_CUBE_FACES];
} fc_scene_part;

fc_scene_part *fc_scene_part_ref(fc_scene_part *part);
/* NULL is ignored. */
void fc_scene_part_unref(fc_scene_part *part);

/* What one connection shows around its fluid; a NULL part is the built-in one
 * (floor and sky; procedural sky). A zeroed struct is the built-in scene. */
typedef struct fc_scene_uploads {
    fc_scene_part *background;
    fc_scene_part *environment;
} fc_scene_uploads;

/* Decode a BACKGROUND / ENVIRONMENT payload into a part with one reference,
 * or *out NULL for an empty payload (back to the built-in one). Errors:
 * FC_ERR_MALFORMED (framing), FC_ERR_INVALID_VALUE (an image that does not
 * decode; faces not square, of different sizes or of different pixel types),
 * FC_ERR_LIMIT (a side beyond FC_SCENE_IMAGE_MAX_SIDE), FC_ERR_NOMEM. */
fc_code fc_scene_part_decode_background(const uint8_t *payload, size_t n, fc_scene_part **out, fc_error *err);
fc_code fc_scene_part_decode_environment(const uint8_t *payload, size_t n, fc_scene_part **out, fc_error *err);

/* Puts `part` (its reference is taken; NULL: the built-in one) in a slot of
 * fc_scene_uploads, dropping the part that was there. */
void fc_scene_uploads_replace(fc_scene_part **slot, fc_scene_part *part);

/* Drops both parts: back to the built-in scene. */
void fc_scene_uploads_free(fc_scene_uploads *u);

#endif
