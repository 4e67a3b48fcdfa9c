/* wire_session.c — PUBLISH, SUBSCRIBE, SESSION_STATE, SESSION_END,
 * LIST_SESSIONS, SESSION_LIST and STREAM_IMAGE (packed frames: wire_packed.c). */
#include "wire_session.h"

#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "wire_io.h"

#define RENDER_FIELDS_SIZE 12u          /* format, quality, aov: RENDER's payload */
#define SUBSCRIBE_FIXED_SIZE (RENDER_FIELDS_SIZE + 8u)
#define SESSION_INFO_FIXED_SIZE 24u     /* producers, viewers, frames, last_frame */
#define SESSION_NAME_MIN_SIZE 3u        /* u16 length + at least one byte */
#define STREAM_TAG_SIZE 24u

/* ---- Session names: u16 length (1..64) + bytes, no NUL ---- */

static size_t name_size(const char *name)
{
    return 2 + strnlen(name, FC_SESSION_NAME_MAX + 1);
}

static fc_code check_name(const char *name, fc_error *err)
{
    size_t len = name ? strnlen(name, FC_SESSION_NAME_MAX + 1) : 0;
    if (len == 0 || len > FC_SESSION_NAME_MAX)
        return fc_error_set(err, FC_ERR_USAGE, "a session name has 1 to %u bytes", FC_SESSION_NAME_MAX);
    return FC_OK;
}

static void put_name(fc_buf *out, const char *name)
{
    size_t len = strnlen(name, FC_SESSION_NAME_MAX);
    wire_put_u16(out, (uint16_t)len);
    wire_put_bytes(out, name, len);
}

/* Read exactly rather than with wire_get_str, which would silently cut a name
 * that is too long (and two long names could then collide). */
static void get_name(wire_reader *r, char *name)
{
    uint16_t len = wire_get_u16(r, "name length");
    const uint8_t *bytes = wire_get_bytes(r, len, "name");
    if (r->code != FC_OK)
        return;
    if (len == 0 || len > FC_SESSION_NAME_MAX)
        wire_fail(r, FC_ERR_INVALID_VALUE, "a session name has 1 to %u bytes, not %u", FC_SESSION_NAME_MAX,
                  (unsigned)len);
    else if (memchr(bytes, '\0', len))
        wire_fail(r, FC_ERR_MALFORMED, "the session name contains a NUL byte");
    else {
        memcpy(name, bytes, len);
        name[len] = '\0';
    }
}

/* A message whose whole payload is a session name (PUBLISH, SESSION_END). */
static fc_code write_named(fc_buf *out, fc_msg_type type, uint32_t request_id, const char *name, fc_error *err)
{
    fc_code code = check_name(name, err);
    if (code != FC_OK)
        return code;
    size_t start = wire_begin_message(out, type, request_id, (uint32_t)name_size(name));
    put_name(out, name);
    return wire_end_message(out, start, err);
}

/* *name is left untouched unless the whole message is valid. */
static fc_code read_named(const uint8_t *p, size_t n, const char *message, char *name, fc_error *err)
{
    char read[FC_SESSION_NAME_MAX + 1];
    wire_reader r = wire_reader_start(p, n, message, err);
    get_name(&r, read);
    wire_expect_end(&r);
    if (r.code != FC_OK)
        return r.code;
    memcpy(name, read, sizeof read);
    return FC_OK;
}

/* ---- PUBLISH ---- */

fc_code fc_wire_write_publish(fc_buf *out, uint32_t request_id, const char *name, fc_error *err)
{
    return write_named(out, FC_MSG_PUBLISH, request_id, name, err);
}

fc_code fc_wire_read_publish(const uint8_t *p, size_t n, char *name, fc_error *err)
{
    return read_named(p, n, "PUBLISH", name, err);
}

/* ---- SUBSCRIBE ---- */

fc_code fc_wire_write_subscribe(fc_buf *out, uint32_t request_id, const fc_subscribe *m, fc_error *err)
{
    fc_code code = check_name(m->name, err);
    if (code != FC_OK)
        return code;
    size_t start = wire_begin_message(out, FC_MSG_SUBSCRIBE, request_id,
                                   (uint32_t)(SUBSCRIBE_FIXED_SIZE + name_size(m->name)));
    wire_put_u32(out, (uint32_t)m->request.format);
    wire_put_u32(out, m->request.quality);
    wire_put_u32(out, (uint32_t)m->request.aov);
    wire_put_u32(out, m->width);
    wire_put_u32(out, m->height);
    put_name(out, m->name);
    return wire_end_message(out, start, err);
}

fc_code fc_wire_read_subscribe(const uint8_t *p, size_t n, fc_subscribe *m, fc_error *err)
{
    fc_subscribe sub = {0};
    wire_reader r = wire_reader_start(p, n, "SUBSCRIBE", err);
    const uint8_t *render_fields = wire_get_bytes(&r, RENDER_FIELDS_SIZE, "format, quality, aov");
    sub.width = wire_get_u32(&r, "width");
    sub.height = wire_get_u32(&r, "height");
    get_name(&r, sub.name);
    wire_expect_end(&r);
    if (r.code != FC_OK)
        return r.code;
    /* The first three fields are RENDER's, with RENDER's rules. */
    fc_code code = fc_wire_read_render(render_fields, RENDER_FIELDS_SIZE, &sub.request, err);
    if (code != FC_OK)
        return code;
    if ((sub.width == 0) != (sub.height == 0))
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "SUBSCRIBE: size %ux%u: give both or neither",
                            (unsigned)sub.width, (unsigned)sub.height);
    /* 4:2:0 video halves both sides. */
    if (sub.request.format == FC_FORMAT_H264 && (sub.width % 2 || sub.height % 2))
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "SUBSCRIBE: H.264 needs an even size, not %ux%u",
                            (unsigned)sub.width, (unsigned)sub.height);
    *m = sub;
    return FC_OK;
}

/* ---- SESSION_STATE and SESSION_LIST entries ---- */

static size_t info_size(const fc_session_info *m)
{
    return SESSION_INFO_FIXED_SIZE + name_size(m->name);
}

static void put_info(fc_buf *out, const fc_session_info *m)
{
    wire_put_u32(out, m->producers);
    wire_put_u32(out, m->viewers);
    wire_put_u64(out, m->frames);
    wire_put_u64(out, m->last_frame);
    put_name(out, m->name);
}

static void get_info(wire_reader *r, fc_session_info *m)
{
    m->producers = wire_get_u32(r, "producers");
    m->viewers = wire_get_u32(r, "viewers");
    m->frames = wire_get_u64(r, "frames");
    m->last_frame = wire_get_u64(r, "last_frame");
    get_name(r, m->name);
}

fc_code fc_wire_write_session_state(fc_buf *out, uint32_t request_id, const fc_session_info *m, fc_error *err)
{
    fc_code code = check_name(m->name, err);
    if (code != FC_OK)
        return code;
    size_t start = wire_begin_message(out, FC_MSG_SESSION_STATE, request_id, (uint32_t)info_size(m));
    put_info(out, m);
    return wire_end_message(out, start, err);
}

fc_code fc_wire_read_session_state(const uint8_t *p, size_t n, fc_session_info *m, fc_error *err)
{
    fc_session_info info;
    memset(&info, 0, sizeof info);
    wire_reader r = wire_reader_start(p, n, "SESSION_STATE", err);
    get_info(&r, &info);
    wire_expect_end(&r);
    if (r.code != FC_OK)
        return r.code;
    *m = info;
    return FC_OK;
}

fc_code fc_wire_write_list_sessions(fc_buf *out, uint32_t request_id, fc_error *err)
{
    return wire_write_empty(out, FC_MSG_LIST_SESSIONS, request_id, err);
}

fc_code fc_wire_read_list_sessions(const uint8_t *p, size_t n, fc_error *err)
{
    return wire_read_empty(p, n, "LIST_SESSIONS", err);
}

fc_code fc_wire_write_session_list(fc_buf *out, uint32_t request_id, const fc_session_info *sessions,
                                   uint32_t count, fc_error *err)
{
    uint64_t length = 4;
    for (uint32_t i = 0; i < count; i++) {
        fc_code code = check_name(sessions[i].name, err);
        if (code != FC_OK)
            return code;
        length += info_size(&sessions[i]);
    }
    fc_code code = wire_check_length(length, 0, 1, "SESSION_LIST", err);
    if (code != FC_OK)
        return code;
    size_t start = wire_begin_message(out, FC_MSG_SESSION_LIST, request_id, (uint32_t)length);
    wire_put_u32(out, count);
    for (uint32_t i = 0; i < count; i++)
        put_info(out, &sessions[i]);
    return wire_end_message(out, start, err);
}

fc_code fc_wire_read_session_list(const uint8_t *p, size_t n, fc_session_info **sessions, uint32_t *count,
                                  fc_error *err)
{
    *sessions = NULL;
    *count = 0;
    wire_reader r = wire_reader_start(p, n, "SESSION_LIST", err);
    uint32_t entries = wire_get_u32(&r, "count");
    /* Checked before allocating, so a corrupt count cannot ask for gigabytes. */
    if (r.code == FC_OK && entries > wire_remaining(&r) / (SESSION_INFO_FIXED_SIZE + SESSION_NAME_MIN_SIZE))
        wire_fail(&r, FC_ERR_MALFORMED, "%u sessions do not fit the payload", entries);
    if (r.code != FC_OK)
        return r.code;
    fc_session_info *list = calloc(entries ? entries : 1, sizeof *list);
    if (!list)
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for %u sessions", entries);
    for (uint32_t i = 0; i < entries && r.code == FC_OK; i++)
        get_info(&r, &list[i]);
    wire_expect_end(&r);
    if (r.code != FC_OK) {
        free(list);
        return r.code;
    }
    *sessions = list;
    *count = entries;
    return FC_OK;
}

/* ---- SESSION_END ---- */

fc_code fc_wire_write_session_leave(fc_buf *out, uint32_t request_id, fc_error *err)
{
    return wire_write_empty(out, FC_MSG_SESSION_END, request_id, err);
}

fc_code fc_wire_read_session_leave(const uint8_t *p, size_t n, fc_error *err)
{
    return wire_read_empty(p, n, "SESSION_END", err);
}

fc_code fc_wire_write_session_end(fc_buf *out, uint32_t request_id, const char *name, fc_error *err)
{
    return write_named(out, FC_MSG_SESSION_END, request_id, name, err);
}

fc_code fc_wire_read_session_end(const uint8_t *p, size_t n, char *name, fc_error *err)
{
    return read_named(p, n, "SESSION_END", name, err);
}

/* ---- STREAM_IMAGE ---- */

/* Written as an IMAGE message whose payload is then moved up to make room for
 * the tag, so the IMAGE layout has exactly one writer (wire.c). */
fc_code fc_wire_write_stream_image(fc_buf *out, uint32_t request_id, const fc_stream_tag *tag,
                                   const fc_image_reply *image, fc_error *err)
{
    size_t start = out->len;
    fc_code code = fc_wire_write_image(out, request_id, image, err);
    if (code != FC_OK)
        return code;
    size_t image_payload = out->len - start - FC_WIRE_HEADER_SIZE;
    code = wire_check_length(STREAM_TAG_SIZE, image_payload, 1, "STREAM_IMAGE", err);
    if (code == FC_OK && !fc_buf_reserve(out, STREAM_TAG_SIZE))
        code = fc_error_set(err, FC_ERR_NOMEM, "out of memory while encoding STREAM_IMAGE");
    if (code != FC_OK) {
        out->len = start;
        return code;
    }
    uint8_t *payload = out->data + start + FC_WIRE_HEADER_SIZE;
    memmove(payload + STREAM_TAG_SIZE, payload, image_payload);
    wire_store_le(payload, tag->frame_number, 8);
    wire_store_le(payload + 8, tag->sequence, 8);
    wire_store_le(payload + 16, tag->missed, 4);
    wire_store_le(payload + 20, tag->flags, 4);
    fc_msg_header h = {.type = FC_MSG_STREAM_IMAGE, .flags = 0, .request_id = request_id,
                       .length = (uint32_t)(STREAM_TAG_SIZE + image_payload)};
    fc_wire_encode_header(out->data + start, &h);
    out->len += STREAM_TAG_SIZE;
    return FC_OK;
}

fc_code fc_wire_read_stream_image(const uint8_t *p, size_t n, fc_stream_tag *tag, fc_image_reply *image,
                                  fc_error *err)
{
    fc_stream_tag read = {0};
    wire_reader r = wire_reader_start(p, n, "STREAM_IMAGE", err);
    read.frame_number = wire_get_u64(&r, "frame_number");
    read.sequence = wire_get_u64(&r, "sequence");
    read.missed = wire_get_u32(&r, "missed");
    read.flags = wire_get_u32(&r, "flags");
    if (r.code != FC_OK)
        return r.code;
    fc_code code = fc_wire_read_image(p + STREAM_TAG_SIZE, n - STREAM_TAG_SIZE, image, err);
    if (code != FC_OK)
        return code;
    *tag = read;
    return FC_OK;
}

/* ---- Capabilities ---- */

uint32_t fc_msg_capabilities(uint16_t type)
{
    switch (type) {
    case FC_MSG_PUBLISH:
    case FC_MSG_SUBSCRIBE:
    case FC_MSG_SESSION_STATE:
    case FC_MSG_SESSION_END:
    case FC_MSG_STREAM_IMAGE:
    case FC_MSG_CHUNK:
    case FC_MSG_LIST_SESSIONS:
    case FC_MSG_SESSION_LIST: return FC_CAP_SESSIONS;
    case FC_MSG_FRAME_PACKED: return FC_CAP_ZSTD | FC_CAP_QUANTIZE16;
    }
    return 0;
}

uint32_t fc_pack_allowed(uint32_t capabilities)
{
    uint32_t allowed = 0;
    if (capabilities & FC_CAP_ZSTD)
        allowed |= FC_PACK_ZSTD;
    if (capabilities & FC_CAP_QUANTIZE16)
        allowed |= FC_PACK_QUANTIZE16;
    return allowed;
}
