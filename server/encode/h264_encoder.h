/* h264_encoder.h — one H.264 video stream: libx264 through libavcodec, tuned
 * for latency (no B-frames, no lookahead, one frame in, one access unit out),
 * RGBA8 images converted to yuv420p with libswscale. Each call returns one
 * access unit in Annex B byte stream format; every IDR frame carries its SPS
 * and PPS, so a decoder can start at any of them (PROTOCOL.md 10.7).
 *
 * An encoder is not thread-safe: one thread at a time, frames in order. */
#ifndef FC_H264_ENCODER_H
#define FC_H264_ENCODER_H

#include <stdbool.h>
#include <stdint.h>

#include "fluidcast_types.h"
#include "wire.h"
#include "image.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct fc_h264_encoder fc_h264_encoder;

/* x264's constant-rate factor for a request's quality 1..100 (PROTOCOL.md
 * 10.7): round(51 - 0.31 q), so the default quality 90 gives x264's own
 * default 23 and 100 gives 20 (visually lossless); lower is better. */
uint32_t fc_h264_crf_for_quality(uint32_t quality);

/* What an encoder for width x height holds, estimated from measurement
 * (libx264 0.164 at these settings held 20 to 30 bytes per pixel from 4K down
 * to 720p, more below): 24 bytes per pixel plus 4 MiB. */
uint64_t fc_h264_encoder_memory(uint32_t width, uint32_t height);

/* An encoder for width x height RGBA8 images at `quality` (as above).
 * FC_ERR_ENCODE for an odd width or height (4:2:0 halves both) or when
 * libavcodec has no libx264; FC_ERR_NOMEM when out of memory. */
fc_code fc_h264_encoder_create(uint32_t width, uint32_t height, uint32_t quality, fc_h264_encoder **out,
                               fc_error *err);
/* NULL is ignored. */
void fc_h264_encoder_free(fc_h264_encoder *enc);

uint32_t fc_h264_encoder_width(const fc_h264_encoder *enc);
uint32_t fc_h264_encoder_height(const fc_h264_encoder *enc);

/* Encodes img (U8, 4 channels, the encoder's size) as the stream's next
 * frame and appends its access unit to `out`; an IDR frame when
 * `force_keyframe` (and for the stream's first frame). *keyframe says
 * whether it is one. FC_ERR_ENCODE when the image does not fit the encoder
 * or libavcodec fails; the encoder should then be freed (its reference
 * frames may be lost). */
fc_code fc_h264_encoder_encode(fc_h264_encoder *enc, const fc_image *img, bool force_keyframe, fc_buf *out,
                               bool *keyframe, fc_error *err);

#ifdef __cplusplus
}
#endif
#endif
