/* wire_scene.h — the scene messages: a client's own background image
 * (BACKGROUND, type 10) and environment cube map (ENVIRONMENT, type 11), sent
 * as encoded image files (PNG, JPEG or EXR). Normative description:
 * proto/PROTOCOL.md, "Scene images". Same conventions as wire.h; this codec
 * only frames the files, the daemon decodes them. */
#ifndef FC_WIRE_SCENE_H
#define FC_WIRE_SCENE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "fluidcast_types.h"
#include "wire.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FC_SCENE_IMAGE_MAX_SIDE 8192u   /* largest width or height of any scene image, in pixels */
#define FC_CUBE_FACES 6                 /* +X, -X, +Y, -Y, +Z, -Z */

/* Bytes of one encoded image file, not owned: decoded messages point into their payload. */
typedef struct fc_encoded_image {
    const uint8_t *data;
    uint64_t size;
} fc_encoded_image;

/* "+X", "-X", "+Y", "-Y", "+Z" or "-Z" for face 0..5, for messages. */
const char *fc_cube_face_name(int face);

/* BACKGROUND: the file's bytes are the whole payload; image NULL (or size 0)
 * sends the empty payload that restores the built-in floor and sky. */
fc_code fc_wire_write_background(fc_buf *out, uint32_t request_id, const fc_encoded_image *image, fc_error *err);

/* ENVIRONMENT: faces[6] in the order +X, -X, +Y, -Y, +Z, -Z, each a u64 length
 * and the bytes; faces NULL sends the empty payload that restores the
 * procedural sky. FC_ERR_INVALID_VALUE for an empty face. */
fc_code fc_wire_write_environment(fc_buf *out, uint32_t request_id, const fc_encoded_image *faces, fc_error *err);

/* image->data points into p; an empty payload gives size 0 ("built-in scene"). */
fc_code fc_wire_read_background(const uint8_t *p, size_t n, fc_encoded_image *image, fc_error *err);

/* *has_faces false for the empty payload ("procedural sky"); else faces[6]
 * point into p. MALFORMED when the lengths do not add up to the payload,
 * INVALID_VALUE for an empty face. */
fc_code fc_wire_read_environment(const uint8_t *p, size_t n, fc_encoded_image faces[FC_CUBE_FACES], bool *has_faces,
                                 fc_error *err);

#ifdef __cplusplus
}
#endif
#endif
