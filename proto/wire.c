/* wire.c — the protocol v1 codecs of HELLO, WELCOME, CAMERA, RENDER, IMAGE,
 * ERROR and GOODBYE (framing: wire_io.c, FRAME: wire_frame.c, SETTINGS:
 * wire_settings.c). */
#include "wire.h"

#include <string.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "wire_io.h"

#define WELCOME_FIXED_SIZE 28u
#define HELLO_FIXED_SIZE 12u
#define CAMERA_SIZE 48u
#define RENDER_SIZE 12u
#define IMAGE_FIXED_SIZE 28u    /* width .. stage count, plus the data size */
#define STAGE_ENTRY_SIZE 8u
#define MAX_WIRE_CODE 99u

/* ---- HELLO / WELCOME ---- */

fc_code fc_wire_write_hello(fc_buf *out, uint32_t request_id, const fc_hello *m, fc_error *err)
{
    /* The token is appended only when there is one, so a HELLO without it is byte for byte the old one. */
    bool has_token = m->token[0] != '\0';
    size_t length = HELLO_FIXED_SIZE + wire_str_size(m->client_name, sizeof m->client_name) +
                    (has_token ? wire_str_size(m->token, sizeof m->token) : 0);
    size_t start = wire_begin_message(out, FC_MSG_HELLO, request_id, (uint32_t)length);
    wire_put_u32(out, m->version_min);
    wire_put_u32(out, m->version_max);
    wire_put_u32(out, m->capabilities);
    wire_put_str(out, m->client_name, sizeof m->client_name);
    if (has_token)
        wire_put_str(out, m->token, sizeof m->token);
    return wire_end_message(out, start, err);
}

/* Bytes after client_name stay ignorable (4.1): ones that do not form a
 * token of at most FC_HELLO_TOKEN_MAX bytes count as no token. Never cut a
 * long one to a prefix, which could match a shorter secret. */
static void read_hello_token(const wire_reader *r, fc_hello *hello)
{
    size_t left = wire_remaining(r);
    const uint8_t *field = r->p + r->pos;
    size_t len = left >= 2 ? (size_t)(field[0] | field[1] << 8) : SIZE_MAX;
    if (len > FC_HELLO_TOKEN_MAX || len > left - 2 || memchr(field + 2, '\0', len))
        return;
    memcpy(hello->token, field + 2, len);
    hello->token[len] = '\0';
}

fc_code fc_wire_read_hello(const uint8_t *p, size_t n, fc_hello *m, fc_error *err)
{
    fc_hello hello = {0};
    wire_reader r = wire_reader_start(p, n, "HELLO", err);
    hello.version_min = wire_get_u32(&r, "version_min");
    hello.version_max = wire_get_u32(&r, "version_max");
    hello.capabilities = wire_get_u32(&r, "capabilities");
    wire_get_str(&r, hello.client_name, sizeof hello.client_name, "client_name");
    if (r.code == FC_OK && wire_remaining(&r) > 0)
        read_hello_token(&r, &hello);
    /* No wire_expect_end: HELLO must be readable by every version, so later
     * versions may append fields that this one ignores (PROTOCOL.md). */
    if (r.code != FC_OK)
        return r.code;
    *m = hello;
    return FC_OK;
}

fc_code fc_wire_write_welcome(fc_buf *out, uint32_t request_id, const fc_welcome *m, fc_error *err)
{
    bool device = (m->capabilities & FC_CAP_DEVICE) != 0;
    size_t length = WELCOME_FIXED_SIZE + wire_str_size(m->server_version, sizeof m->server_version) +
                    wire_str_size(m->renderer, sizeof m->renderer) +
                    (device ? wire_str_size(m->device, sizeof m->device) : 0);
    size_t start = wire_begin_message(out, FC_MSG_WELCOME, request_id, (uint32_t)length);
    wire_put_u32(out, m->version);
    wire_put_u32(out, m->capabilities);
    wire_put_u64(out, m->limits.max_particles);
    wire_put_u32(out, m->limits.max_width);
    wire_put_u32(out, m->limits.max_height);
    wire_put_u32(out, m->limits.max_message);
    wire_put_str(out, m->server_version, sizeof m->server_version);
    wire_put_str(out, m->renderer, sizeof m->renderer);
    if (device)
        wire_put_str(out, m->device, sizeof m->device);
    return wire_end_message(out, start, err);
}

fc_code fc_wire_read_welcome(const uint8_t *p, size_t n, fc_welcome *m, fc_error *err)
{
    fc_welcome welcome = {0};
    wire_reader r = wire_reader_start(p, n, "WELCOME", err);
    welcome.version = wire_get_u32(&r, "version");
    welcome.capabilities = wire_get_u32(&r, "capabilities");
    welcome.limits.max_particles = wire_get_u64(&r, "max_particles");
    welcome.limits.max_width = wire_get_u32(&r, "max_width");
    welcome.limits.max_height = wire_get_u32(&r, "max_height");
    welcome.limits.max_message = wire_get_u32(&r, "max_message");
    wire_get_str(&r, welcome.server_version, sizeof welcome.server_version, "server_version");
    wire_get_str(&r, welcome.renderer, sizeof welcome.renderer, "renderer");
    if (welcome.capabilities & FC_CAP_DEVICE)
        wire_get_str(&r, welcome.device, sizeof welcome.device, "device");
    wire_expect_end(&r);
    if (r.code != FC_OK)
        return r.code;
    *m = welcome;
    return FC_OK;
}

/* ---- CAMERA ---- */

fc_code fc_wire_write_camera(fc_buf *out, uint32_t request_id, const fc_camera *m, fc_error *err)
{
    size_t start = wire_begin_message(out, FC_MSG_CAMERA, request_id, CAMERA_SIZE);
    wire_put_f32_array(out, m->eye, 3);
    wire_put_f32_array(out, m->target, 3);
    wire_put_f32_array(out, m->up, 3);
    wire_put_f32(out, m->fov_y_deg);
    wire_put_u32(out, m->width);
    wire_put_u32(out, m->height);
    return wire_end_message(out, start, err);
}

fc_code fc_wire_read_camera(const uint8_t *p, size_t n, fc_camera *m, fc_error *err)
{
    fc_camera cam = {0};
    wire_reader r = wire_reader_start(p, n, "CAMERA", err);
    wire_get_f32_array(&r, cam.eye, 3, "eye");
    wire_get_f32_array(&r, cam.target, 3, "target");
    wire_get_f32_array(&r, cam.up, 3, "up");
    cam.fov_y_deg = wire_get_f32(&r, "fov_y_deg");
    cam.width = wire_get_u32(&r, "width");
    cam.height = wire_get_u32(&r, "height");
    wire_expect_end(&r);
    if (r.code != FC_OK)
        return r.code;
    fc_code code = fc_camera_validate(&cam, err);
    if (code != FC_OK)
        return code;
    *m = cam;
    return FC_OK;
}

/* ---- RENDER ---- */

static bool is_known_format(uint32_t format)
{
    return format >= FC_FORMAT_PNG && format <= FC_FORMAT_H264;
}

static bool is_known_aov(uint32_t aov)
{
    return aov <= FC_AOV_NOISE;
}

fc_code fc_wire_write_render(fc_buf *out, uint32_t request_id, const fc_render_request *m, fc_error *err)
{
    size_t start = wire_begin_message(out, FC_MSG_RENDER, request_id, RENDER_SIZE);
    wire_put_u32(out, (uint32_t)m->format);
    wire_put_u32(out, m->quality);
    wire_put_u32(out, (uint32_t)m->aov);
    return wire_end_message(out, start, err);
}

fc_code fc_wire_read_render(const uint8_t *p, size_t n, fc_render_request *m, fc_error *err)
{
    wire_reader r = wire_reader_start(p, n, "RENDER", err);
    uint32_t format = wire_get_u32(&r, "format");
    uint32_t quality = wire_get_u32(&r, "quality");
    uint32_t aov = wire_get_u32(&r, "aov");
    wire_expect_end(&r);
    if (r.code != FC_OK)
        return r.code;
    if (!is_known_format(format))
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "RENDER: unknown image format %u", format);
    if (quality > 100)
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "RENDER: quality %u is outside 0..100", quality);
    if (!is_known_aov(aov))
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "RENDER: unknown aov %u", aov);
    /* PNG, JPEG and H.264 hold 8-bit colour; depth and thickness are unbounded floats. */
    if (aov != FC_AOV_COLOR && (format == FC_FORMAT_PNG || format == FC_FORMAT_JPEG || format == FC_FORMAT_H264))
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "RENDER: aov %u needs EXR or RAW, not format %u", aov,
                            format);
    m->format = (fc_image_format)format;
    m->quality = quality ? quality : FC_DEFAULT_QUALITY;
    m->aov = (fc_aov)aov;
    return FC_OK;
}

/* ---- IMAGE ---- */

static bool stage_measured(float ms)
{
    return ms >= 0.0f;
}

fc_code fc_wire_write_image(fc_buf *out, uint32_t request_id, const fc_image_reply *m, fc_error *err)
{
    uint32_t stages = 0;
    for (int s = 0; s < FC_STAGE_COUNT; s++)
        stages += stage_measured(m->stage_ms[s]);
    uint64_t fixed = IMAGE_FIXED_SIZE + (uint64_t)stages * STAGE_ENTRY_SIZE;
    fc_code code = wire_check_length(fixed, m->size, 1, "IMAGE", err);
    if (code != FC_OK)
        return code;
    size_t start = wire_begin_message(out, FC_MSG_IMAGE, request_id, (uint32_t)(fixed + m->size));
    wire_put_u32(out, m->width);
    wire_put_u32(out, m->height);
    wire_put_u32(out, (uint32_t)m->format);
    wire_put_u32(out, (uint32_t)m->aov);
    wire_put_u32(out, stages);
    for (int s = 0; s < FC_STAGE_COUNT; s++) {
        if (!stage_measured(m->stage_ms[s]))
            continue;
        wire_put_u32(out, (uint32_t)s);
        wire_put_f32(out, m->stage_ms[s]);
    }
    wire_put_u64(out, m->size);
    wire_put_bytes(out, m->data, (size_t)m->size);
    return wire_end_message(out, start, err);
}

fc_code fc_wire_read_image(const uint8_t *p, size_t n, fc_image_reply *m, fc_error *err)
{
    fc_image_reply image = {0};
    for (int s = 0; s < FC_STAGE_COUNT; s++)
        image.stage_ms[s] = -1.0f;
    wire_reader r = wire_reader_start(p, n, "IMAGE", err);
    image.width = wire_get_u32(&r, "width");
    image.height = wire_get_u32(&r, "height");
    uint32_t format = wire_get_u32(&r, "format");
    uint32_t aov = wire_get_u32(&r, "aov");
    uint32_t stages = wire_get_u32(&r, "stage count");
    if (r.code == FC_OK && stages > wire_remaining(&r) / STAGE_ENTRY_SIZE)
        wire_fail(&r, FC_ERR_MALFORMED, "%u stage timings do not fit the payload", stages);
    for (uint32_t i = 0; i < stages && r.code == FC_OK; i++) {
        uint32_t stage = wire_get_u32(&r, "stage");
        float ms = wire_get_f32(&r, "stage time");
        /* Stages this version does not know are skipped: later servers may time more. */
        if (stage < FC_STAGE_COUNT)
            image.stage_ms[stage] = ms;
    }
    image.size = wire_get_u64(&r, "data size");
    if (r.code == FC_OK && image.size != wire_remaining(&r))
        wire_fail(&r, FC_ERR_MALFORMED, "data size %llu but %zu bytes follow", (unsigned long long)image.size,
                  wire_remaining(&r));
    image.data = wire_get_bytes(&r, (size_t)image.size, "data");
    if (r.code != FC_OK)
        return r.code;
    if (!is_known_format(format) || !is_known_aov(aov))
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "IMAGE: unknown format %u or aov %u", format, aov);
    image.format = (fc_image_format)format;
    image.aov = (fc_aov)aov;
    *m = image;
    return FC_OK;
}

/* ---- ERROR / GOODBYE ---- */

fc_code fc_wire_write_error(fc_buf *out, uint32_t request_id, const fc_error *m, fc_error *err)
{
    if (m->code < 1 || (unsigned)m->code > MAX_WIRE_CODE)
        return fc_error_set(err, FC_ERR_USAGE, "code %d is local to this process and never sent", (int)m->code);
    size_t length = 4 + wire_str_size(m->message, sizeof m->message);
    size_t start = wire_begin_message(out, FC_MSG_ERROR, request_id, (uint32_t)length);
    wire_put_u32(out, (uint32_t)m->code);
    wire_put_str(out, m->message, sizeof m->message);
    return wire_end_message(out, start, err);
}

fc_code fc_wire_read_error(const uint8_t *p, size_t n, fc_error *m, fc_error *err)
{
    fc_error received = {0};
    wire_reader r = wire_reader_start(p, n, "ERROR", err);
    uint32_t code = wire_get_u32(&r, "code");
    wire_get_str(&r, received.message, sizeof received.message, "message");
    wire_expect_end(&r);
    if (r.code == FC_OK && (code < 1 || code > MAX_WIRE_CODE))
        wire_fail(&r, FC_ERR_MALFORMED, "code %u is not a wire code (1..99)", code);
    if (r.code != FC_OK)
        return r.code;
    /* Codes this version does not name are kept as they are: fc_code_name calls them "unknown". */
    received.code = (fc_code)code;
    *m = received;
    return FC_OK;
}

fc_code fc_wire_write_goodbye(fc_buf *out, uint32_t request_id, fc_error *err)
{
    return wire_write_empty(out, FC_MSG_GOODBYE, request_id, err);
}

fc_code fc_wire_read_goodbye(const uint8_t *p, size_t n, fc_error *err)
{
    return wire_read_empty(p, n, "GOODBYE", err);
}
