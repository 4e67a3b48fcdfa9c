/* wire.h — the protocol v1 codec: framing and every message's byte layout
 * (normative description: proto/PROTOCOL.md). Pure C: no sockets, no GL.
 *
 * Encoders append one complete message (header + payload) to an fc_buf.
 * Decoders take one payload (the bytes after the header, exactly header.length
 * long), check every length and count before reading, and never read past it. */
#ifndef FC_WIRE_H
#define FC_WIRE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include "fluidcast_types.h"

#ifdef __cplusplus
extern "C" {
#endif

#define FC_PROTOCOL_VERSION 1u
#define FC_WIRE_MAGIC "FCST"           /* first four bytes of every message */
#define FC_WIRE_HEADER_SIZE 16u
#define FC_DEFAULT_QUALITY 90u         /* what RENDER's quality 0 means */

/* Every message type of the protocol, X(NAME, number), in the order and with
 * the numbers of PROTOCOL.md section 7's table (tests/proto/test_msg_types.c
 * holds the two equal). Both fc_msg_type (FC_MSG_HELLO = 1, ...) and
 * fc_msg_name are made from this one list, so a type cannot lack its name.
 * Numbers are the wire's: never renumber. Types 10 and up are extensions
 * (PROTOCOL.md 9): scene images (wire_scene.h), meshes (wire_mesh.h), and the
 * session and packed-upload messages (wire_session.h), which need a capability,
 * and surface meshes (wire_surface.h). */
#define FC_MSG_TYPES(X)                                                                                     \
    X(HELLO, 1)            /* client -> server */                                                           \
    X(WELCOME, 2)          /* server -> client */                                                           \
    X(FRAME, 3)            /* client -> server */                                                           \
    X(CAMERA, 4)           /* client -> server */                                                           \
    X(SETTINGS, 5)         /* client -> server */                                                           \
    X(RENDER, 6)           /* client -> server */                                                           \
    X(IMAGE, 7)            /* server -> client */                                                           \
    X(ERROR, 8)            /* server -> client */                                                           \
    X(GOODBYE, 9)          /* either way */                                                                 \
    X(BACKGROUND, 10)      /* client -> server: background image file, or empty */                         \
    X(ENVIRONMENT, 11)     /* client -> server: six cube-map face files, or empty */                        \
    X(MESH, 12)            /* client -> server: one mesh, or the removal of one */                          \
    X(MESH_TRANSFORM, 13)  /* client -> server: new transforms of meshes already sent */                    \
    X(PUBLISH, 16)         /* client -> server: become a producer of a named session */                     \
    X(SUBSCRIBE, 17)       /* client -> server: become a viewer of a named session */                       \
    X(SESSION_STATE, 18)   /* server -> client: answers PUBLISH / SUBSCRIBE */                              \
    X(SESSION_END, 19)     /* either way: leave a session / the session is over */                          \
    X(STREAM_IMAGE, 20)    /* server -> viewer: one rendered frame of the session */                        \
    X(CHUNK, 21)           /* producer -> server: chunk i of K of a multi-rank frame */                     \
    X(FRAME_PACKED, 22)    /* client -> server: a FRAME in a packed body */                                 \
    X(LIST_SESSIONS, 23)   /* client -> server: which sessions exist */                                     \
    X(SESSION_LIST, 24)    /* server -> client: answers LIST_SESSIONS */                                   \
    X(SURFACE, 25)         /* client -> server: the surface mesh of the frame RENDER would render */      \
    X(SURFACE_PART, 26)    /* server -> client: one part of SURFACE's answer */

#define FC_MSG_ENUMERATOR(name, number) FC_MSG_##name = number,
typedef enum fc_msg_type { FC_MSG_TYPES(FC_MSG_ENUMERATOR) } fc_msg_type;
#undef FC_MSG_ENUMERATOR

/* The upper-case name of a message type as PROTOCOL.md writes it, e.g.
 * "WELCOME" for 2; NULL for a number no message type has. */
const char *fc_msg_name(uint16_t type);

typedef struct fc_msg_header {
    uint16_t type;         /* fc_msg_type */
    uint16_t flags;        /* 0 in v1 */
    uint32_t request_id;   /* chosen by the client; replies echo the id of the message they answer */
    uint32_t length;       /* payload bytes following the header */
} fc_msg_header;

/* Growable output buffer. On allocation failure `failed` is set and later
 * appends are ignored; the encoders then return FC_ERR_NOMEM. */
typedef struct fc_buf {
    uint8_t *data;
    size_t len;
    size_t cap;
    bool failed;
} fc_buf;

void fc_buf_init(fc_buf *b);
void fc_buf_free(fc_buf *b);
void fc_buf_reset(fc_buf *b);                 /* len = 0, keeps capacity */
bool fc_buf_reserve(fc_buf *b, size_t extra); /* ensure cap >= len + extra */

/* ---- Framing ---- */
void fc_wire_encode_header(uint8_t out[FC_WIRE_HEADER_SIZE], const fc_msg_header *h);
/* FC_ERR_BAD_MAGIC, or FC_ERR_TOO_LARGE when length > max_payload. */
fc_code fc_wire_decode_header(const uint8_t in[FC_WIRE_HEADER_SIZE], uint32_t max_payload,
                              fc_msg_header *h, fc_error *err);

/* ---- Messages ---- */
/* Longest authentication token HELLO may carry; a longer one is read as none. */
#define FC_HELLO_TOKEN_MAX 256

typedef struct fc_hello {
    uint32_t version_min;      /* lowest protocol version the client speaks */
    uint32_t version_max;      /* highest */
    uint32_t capabilities;     /* requested capability bits; none defined in v1 */
    char client_name[64];      /* NUL-terminated, informational */
    char token[FC_HELLO_TOKEN_MAX + 1]; /* shared secret after client_name; "" = none sent (PROTOCOL.md 7.1) */
} fc_hello;

typedef struct fc_limits {
    uint64_t max_particles;    /* per frame */
    uint32_t max_width;        /* image width */
    uint32_t max_height;
    uint32_t max_message;      /* payload bytes of one message */
} fc_limits;

/* Capability bit 3 (PROTOCOL.md 9): WELCOME carries `device` after
 * `renderer`. Asked for by clients that read it; a server that does not grant
 * it (an older one) sends WELCOME without it, and older clients never ask. */
#define FC_CAP_DEVICE (1u << 3)

typedef struct fc_welcome {
    uint32_t version;          /* the version chosen for this connection */
    uint32_t capabilities;     /* granted capability bits */
    fc_limits limits;
    char server_version[32];   /* e.g. "fluidcastd 0.1.0" */
    char renderer[128];        /* GL_RENDERER of the daemon's context */
    char device[128];          /* the GPU device, e.g. "EGL device 0, /dev/dri/renderD128, CUDA 0";
                                  on the wire only with FC_CAP_DEVICE granted, else "" */
} fc_welcome;

typedef struct fc_image_reply {
    uint32_t width, height;
    fc_image_format format;
    fc_aov aov;
    float stage_ms[FC_STAGE_COUNT];  /* server timings; negative = not measured */
    const uint8_t *data;             /* encoded image; points into the decoded payload */
    uint64_t size;
} fc_image_reply;

fc_code fc_wire_write_hello(fc_buf *out, uint32_t request_id, const fc_hello *m, fc_error *err);
fc_code fc_wire_write_welcome(fc_buf *out, uint32_t request_id, const fc_welcome *m, fc_error *err);
fc_code fc_wire_write_frame(fc_buf *out, uint32_t request_id, const fc_frame *m, fc_error *err);

/* A part of a message that stays where its owner keeps it. */
typedef struct fc_wire_span {
    const void *data;
    size_t size;
} fc_wire_span;
/* At most this many particle arrays follow FRAME's fixed fields. */
#define FC_WIRE_FRAME_ARRAYS 5
/* FRAME for a sender that hands the particle arrays to the socket where they
 * lie (sendmsg) instead of copying them into the message: appends the header
 * and fixed fields to `out` and lists the arrays, to be sent right after out's
 * bytes, in `arrays` (*array_count of them). On a little-endian host the arrays
 * already are the wire's bytes; on others they are encoded into `out` as
 * fc_wire_write_frame does, and *array_count is 0. */
fc_code fc_wire_write_frame_parts(fc_buf *out, uint32_t request_id, const fc_frame *m,
                                  fc_wire_span arrays[FC_WIRE_FRAME_ARRAYS], size_t *array_count, fc_error *err);
fc_code fc_wire_write_camera(fc_buf *out, uint32_t request_id, const fc_camera *m, fc_error *err);
/* Writes every field of *m as key/value entries. */
fc_code fc_wire_write_settings(fc_buf *out, uint32_t request_id, const fc_settings *m, fc_error *err);
/* A SETTINGS without entries: it changes nothing; a viewer sends it to ask for
 * an H.264 key frame (PROTOCOL.md 10.7). */
fc_code fc_wire_write_settings_none(fc_buf *out, uint32_t request_id, fc_error *err);
fc_code fc_wire_write_render(fc_buf *out, uint32_t request_id, const fc_render_request *m, fc_error *err);
fc_code fc_wire_write_image(fc_buf *out, uint32_t request_id, const fc_image_reply *m, fc_error *err);
/* code must be a wire code (1..99). */
fc_code fc_wire_write_error(fc_buf *out, uint32_t request_id, const fc_error *m, fc_error *err);
fc_code fc_wire_write_goodbye(fc_buf *out, uint32_t request_id, fc_error *err);

fc_code fc_wire_read_hello(const uint8_t *p, size_t n, fc_hello *m, fc_error *err);
fc_code fc_wire_read_welcome(const uint8_t *p, size_t n, fc_welcome *m, fc_error *err);
/* Allocates the frame's arrays (fc_frame_free releases them). Refuses counts
 * above max_particles with FC_ERR_LIMIT, non-finite values with
 * FC_ERR_INVALID_VALUE, size mismatches with FC_ERR_MALFORMED. */
fc_code fc_wire_read_frame(const uint8_t *p, size_t n, uint64_t max_particles, fc_frame *m, fc_error *err);

/* Storage for frames a server decodes: one block per frame holds all its
 * arrays back to back in FRAME's order (positions, density, velocity, ids),
 * so blocks can be recycled whole. */
typedef struct fc_block_source {
    uint8_t *(*take)(void *ctx, size_t size);   /* NULL when memory runs out */
    void (*give)(void *ctx, uint8_t *block, size_t size);
    void *ctx;
} fc_block_source;

/* A decoded frame whose arrays lie in one place: in `block` (block_size
 * bytes, from the fc_block_source, handed back with its give) or, when block
 * is NULL, in the payload it was decoded from, which must outlive it. */
typedef struct fc_frame_view {
    fc_frame frame;
    uint8_t *block;
    size_t block_size;
} fc_frame_view;

/* FRAME decoded in place, without copying: the view's arrays point into p,
 * which must be 4-byte aligned (FC_ERR_USAGE otherwise); big-endian hosts
 * byte-swap the values there. The same checks and codes as fc_wire_read_frame. */
fc_code fc_wire_view_frame(uint8_t *p, size_t n, uint64_t max_particles, fc_frame *view, fc_error *err);
fc_code fc_wire_read_camera(const uint8_t *p, size_t n, fc_camera *m, fc_error *err);
/* Applies the entries onto *m atomically: on any error *m is unchanged. */
fc_code fc_wire_read_settings(const uint8_t *p, size_t n, fc_settings *m, fc_error *err);
fc_code fc_wire_read_render(const uint8_t *p, size_t n, fc_render_request *m, fc_error *err);
/* m->data points into p: keep p alive while using it. */
fc_code fc_wire_read_image(const uint8_t *p, size_t n, fc_image_reply *m, fc_error *err);
fc_code fc_wire_read_error(const uint8_t *p, size_t n, fc_error *m, fc_error *err);
/* GOODBYE has no payload: FC_ERR_MALFORMED unless n == 0. */
fc_code fc_wire_read_goodbye(const uint8_t *p, size_t n, fc_error *err);

#ifdef __cplusplus
}
#endif
#endif
