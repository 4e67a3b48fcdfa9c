/* wire_session.h — the protocol's session and streaming messages (types 16..24),
 * the capability bits that enable them, and packed (zstd / 16-bit quantised)
 * frame uploads. Normative description: proto/PROTOCOL.md, "Sessions and
 * streaming". Same conventions as wire.h: encoders append one whole message to
 * an fc_buf, decoders take exactly one payload and check every length first. */
#ifndef FC_WIRE_SESSION_H
#define FC_WIRE_SESSION_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "fluidcast_types.h"
#include "wire.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Capability bits of HELLO (requested) and WELCOME (granted). */
enum {
    FC_CAP_SESSIONS = 1u << 0,     /* PUBLISH .. SESSION_LIST (types 16..21, 23, 24) */
    FC_CAP_ZSTD = 1u << 1,         /* packed bodies may be zstd-compressed */
    FC_CAP_QUANTIZE16 = 1u << 2    /* packed bodies may carry 16-bit quantised positions */
};
/* FC_CAP_DEVICE (bit 3, WELCOME's device) is defined with WELCOME in wire.h. */
#define FC_CAPS_ALL (FC_CAP_SESSIONS | FC_CAP_ZSTD | FC_CAP_QUANTIZE16 | FC_CAP_DEVICE)

#define FC_SESSION_NAME_MAX 64u        /* bytes of a session name (UTF-8, no NUL) */
#define FC_CHUNK_COUNT_MAX 4096u       /* ranks K of one multi-rank frame */

/* Encoding bits of a packed body. */
enum {
    FC_PACK_ZSTD = 1u << 0,        /* the body is one zstd frame */
    FC_PACK_QUANTIZE16 = 1u << 1   /* positions as 16-bit offsets in the frame's bounding box */
};
#define FC_PACK_ALL (FC_PACK_ZSTD | FC_PACK_QUANTIZE16)
#define FC_PACK_DEFAULT_ZSTD_LEVEL 3

/* STREAM_IMAGE flags. */
enum {
    FC_STREAM_REFRESH = 1u << 0,   /* lossless re-send of a frame already shown lossy */
    FC_STREAM_VIEW = 1u << 1,      /* re-render of the current frame after this viewer's camera/settings changed */
    FC_STREAM_KEYFRAME = 1u << 2   /* H.264 only: the access unit is an IDR frame (with SPS and PPS), where a
                                      decoder may start */
};

/* What SESSION_STATE and each SESSION_LIST entry say about a session. */
typedef struct fc_session_info {
    char name[FC_SESSION_NAME_MAX + 1];
    uint32_t producers;            /* connections publishing to it */
    uint32_t viewers;              /* connections subscribed to it */
    uint64_t frames;               /* complete frames published so far */
    uint64_t last_frame;           /* frame number of the latest, 0 = none yet */
} fc_session_info;

typedef struct fc_subscribe {
    fc_render_request request;     /* format of the stream images (as RENDER) */
    uint32_t width, height;        /* size of the automatic camera until a CAMERA; 0,0 = server default */
    char name[FC_SESSION_NAME_MAX + 1];
} fc_subscribe;

/* The fields STREAM_IMAGE puts before its IMAGE payload. */
typedef struct fc_stream_tag {
    uint64_t frame_number;         /* the producer's frame number */
    uint64_t sequence;             /* 1-based count of frames published in the session up to this one */
    uint32_t missed;               /* frames published since this viewer's previous image that it never got */
    uint32_t flags;                /* FC_STREAM_* */
} fc_stream_tag;

typedef struct fc_chunk_header {
    uint64_t frame_number;
    uint32_t index;                /* i, 0-based */
    uint32_t count;                /* K */
} fc_chunk_header;

/* ---- Session messages ---- */
fc_code fc_wire_write_publish(fc_buf *out, uint32_t request_id, const char *name, fc_error *err);
fc_code fc_wire_write_subscribe(fc_buf *out, uint32_t request_id, const fc_subscribe *m, fc_error *err);
fc_code fc_wire_write_session_state(fc_buf *out, uint32_t request_id, const fc_session_info *m, fc_error *err);
/* From a client: leave the session (empty payload). */
fc_code fc_wire_write_session_leave(fc_buf *out, uint32_t request_id, fc_error *err);
/* From the server: the session `name` is over for this connection. */
fc_code fc_wire_write_session_end(fc_buf *out, uint32_t request_id, const char *name, fc_error *err);
fc_code fc_wire_write_list_sessions(fc_buf *out, uint32_t request_id, fc_error *err);
fc_code fc_wire_write_session_list(fc_buf *out, uint32_t request_id, const fc_session_info *sessions,
                                   uint32_t count, fc_error *err);
/* STREAM_IMAGE: the tag followed by an IMAGE payload. */
fc_code fc_wire_write_stream_image(fc_buf *out, uint32_t request_id, const fc_stream_tag *tag,
                                   const fc_image_reply *image, fc_error *err);

/* name gets FC_SESSION_NAME_MAX + 1 bytes. INVALID_VALUE for an empty or too long name. */
fc_code fc_wire_read_publish(const uint8_t *p, size_t n, char *name, fc_error *err);
fc_code fc_wire_read_subscribe(const uint8_t *p, size_t n, fc_subscribe *m, fc_error *err);
fc_code fc_wire_read_session_state(const uint8_t *p, size_t n, fc_session_info *m, fc_error *err);
/* A client's SESSION_END: MALFORMED unless n == 0. */
fc_code fc_wire_read_session_leave(const uint8_t *p, size_t n, fc_error *err);
fc_code fc_wire_read_session_end(const uint8_t *p, size_t n, char *name, fc_error *err);
fc_code fc_wire_read_list_sessions(const uint8_t *p, size_t n, fc_error *err);
/* Allocates *sessions (free() it); *count entries. */
fc_code fc_wire_read_session_list(const uint8_t *p, size_t n, fc_session_info **sessions, uint32_t *count,
                                  fc_error *err);
/* image->data points into p. */
fc_code fc_wire_read_stream_image(const uint8_t *p, size_t n, fc_stream_tag *tag, fc_image_reply *image,
                                  fc_error *err);

/* ---- Packed frames (FRAME_PACKED, CHUNK) ----
 * encoding: FC_PACK_* bits; zstd_level 0 = FC_PACK_DEFAULT_ZSTD_LEVEL. */
fc_code fc_wire_write_frame_packed(fc_buf *out, uint32_t request_id, const fc_frame *frame, uint32_t encoding,
                                   int zstd_level, fc_error *err);
fc_code fc_wire_write_chunk(fc_buf *out, uint32_t request_id, const fc_chunk_header *h, const fc_frame *part,
                            uint32_t encoding, int zstd_level, fc_error *err);
/* allowed_encoding: the FC_PACK_* bits this connection negotiated; others are
 * BAD_STATE. Counts above max_particles are LIMIT, non-finite values
 * INVALID_VALUE, inconsistent sizes MALFORMED. Allocates the frame's arrays. */
fc_code fc_wire_read_frame_packed(const uint8_t *p, size_t n, uint32_t allowed_encoding, uint64_t max_particles,
                                  fc_frame *frame, fc_error *err);
/* The header's values are checked by the caller (it knows the frame's other chunks). */
fc_code fc_wire_read_chunk(const uint8_t *p, size_t n, uint32_t allowed_encoding, uint64_t max_particles,
                           fc_chunk_header *h, fc_frame *part, fc_error *err);
/* The same decoded into a view: a plain inner layout in place in p (4-byte
 * aligned; block NULL), a compressed or quantised one into a block from src
 * (a zstd+quantised one also borrows src's block for the decompressed bytes). */
fc_code fc_wire_view_frame_packed(uint8_t *p, size_t n, uint32_t allowed_encoding, uint64_t max_particles,
                                  const fc_block_source *src, fc_frame_view *out, fc_error *err);
fc_code fc_wire_view_chunk(uint8_t *p, size_t n, uint32_t allowed_encoding, uint64_t max_particles,
                           const fc_block_source *src, fc_chunk_header *h, fc_frame_view *part, fc_error *err);

/* The capability bits of which a connection must have been granted one for
 * `type` to be defined on it (PROTOCOL.md 9): FC_CAP_SESSIONS for types 16..21,
 * 23 and 24, FC_CAP_ZSTD | FC_CAP_QUANTIZE16 for FRAME_PACKED; 0 for the types
 * every connection may send. */
uint32_t fc_msg_capabilities(uint16_t type);

/* The FC_PACK_* bits a set of granted capabilities allows. */
uint32_t fc_pack_allowed(uint32_t capabilities);

/* Largest error of a quantised coordinate on an axis spanning [lo, hi]:
 * (hi - lo) / 65535 / 2, before float rounding of the decoded value. */
double fc_quantize_error_bound(float lo, float hi);

#ifdef __cplusplus
}
#endif
#endif
