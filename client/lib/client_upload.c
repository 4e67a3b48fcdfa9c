/* client_upload.c — frames in packed bodies (zstd, 16-bit positions) and the
 * chunks of multi-rank frames, with what each upload cost on the wire. */
#include "fluidcast.h"

#include "client_core.h"
#include "fc_error.h"
#include "fc_frame.h"
#include "wire_session.h"

_Static_assert(FC_UPLOAD_ZSTD == FC_PACK_ZSTD && FC_UPLOAD_QUANTIZE16 == FC_PACK_QUANTIZE16,
               "fluidcast.h upload bits must match the wire's");

#define FRAME_FIXED_SIZE 16u

/* Bytes of the frame as a plain FRAME message: header, fixed fields, arrays. */
static uint64_t plain_size(const fc_frame *frame)
{
    return FC_WIRE_HEADER_SIZE + FRAME_FIXED_SIZE + frame->count * fc_frame_particle_bytes(fc_frame_attributes(frame));
}

static fc_code check_upload(const fc_client *c, const fc_frame *frame, const fc_upload_options *o, fc_error *err)
{
    fc_code code = fc_client_check_usable(c, err);
    if (code != FC_OK)
        return code;
    if (!frame || frame->count == 0 || !frame->positions)
        return fc_error_set(err, FC_ERR_USAGE, "a frame needs at least one particle position");
    uint32_t unknown = o->encoding & ~(uint32_t)FC_PACK_ALL;
    if (unknown)
        return fc_error_set(err, FC_ERR_USAGE, "unknown upload encoding bits 0x%x", unknown);
    uint32_t missing = o->encoding & ~fc_pack_allowed(c->info.capabilities);
    if (missing)
        return fc_error_set(err, FC_ERR_USAGE, "the server did not grant upload encoding 0x%x", missing);
    return FC_OK;
}

static fc_code send_counted(fc_client *c, const fc_frame *frame, const char *what, fc_upload_stats *stats,
                            fc_error *err)
{
    fc_code code = fc_client_check_message_size(c, what, err);
    if (code == FC_OK)
        code = fc_client_send_tx(c, err);
    if (code == FC_OK && stats) {
        stats->raw_bytes = plain_size(frame);
        stats->wire_bytes = c->tx.len;
    }
    return code;
}

fc_code fc_client_upload_frame(fc_client *client, const fc_frame *frame, const fc_upload_options *options,
                               fc_upload_stats *stats, fc_error *err)
{
    const fc_upload_options plain = {0};
    const fc_upload_options *o = options ? options : &plain;
    fc_code code = check_upload(client, frame, o, err);
    if (code != FC_OK)
        return code;
    /* Plain frames go as FRAME, which every server reads, straight from the caller's arrays. */
    if (o->encoding == 0) {
        uint64_t sent = 0;
        code = fc_client_send_frame_message(client, frame, &sent, err);
        if (code == FC_OK && stats)
            *stats = (fc_upload_stats){.raw_bytes = plain_size(frame), .wire_bytes = sent};
        return code;
    }
    fc_buf_reset(&client->tx);
    code = fc_wire_write_frame_packed(&client->tx, fc_client_next_request_id(client), frame, o->encoding,
                                      o->zstd_level, err);
    return code != FC_OK ? code : send_counted(client, frame, "the frame", stats, err);
}

fc_code fc_client_send_chunk(fc_client *client, uint64_t frame_number, uint32_t index, uint32_t count,
                             const fc_frame *part, const fc_upload_options *options, fc_upload_stats *stats,
                             fc_error *err)
{
    const fc_upload_options plain = {0};
    const fc_upload_options *o = options ? options : &plain;
    fc_code code = check_upload(client, part, o, err);
    if (code != FC_OK)
        return code;
    if (!(client->info.capabilities & FC_SERVER_CAN_STREAM))
        return fc_error_set(err, FC_ERR_USAGE, "the server did not grant multi-rank frames (capability 0x%x)",
                            FC_SERVER_CAN_STREAM);
    fc_chunk_header header = {frame_number, index, count};
    fc_buf_reset(&client->tx);
    code = fc_wire_write_chunk(&client->tx, fc_client_next_request_id(client), &header, part, o->encoding,
                               o->zstd_level, err);
    return code != FC_OK ? code : send_counted(client, part, "the chunk", stats, err);
}
