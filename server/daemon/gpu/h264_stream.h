/* h264_stream.h — a viewer's H.264 stream: its encoder (encode/h264_encoder.h),
 * shared by reference between the viewer that owns the stream and the job of
 * its one image in flight, so that a viewer leaving while its image is being
 * encoded frees the encoder when the job is done with it.
 *
 * A viewer has at most one image in flight (conversations/viewer.h), so one encoder
 * thread at a time encodes a stream, its frames in order; the job queues
 * between the threads order the hand-overs. The encoder is made by the first
 * image and again at an image of another size (a resize), each time starting
 * with an IDR frame. */
#ifndef FC_DAEMON_H264_STREAM_H
#define FC_DAEMON_H264_STREAM_H

#include <stdbool.h>
#include <stdint.h>

#include "fc_error.h"
#include "image.h"
#include "wire.h"

typedef struct fc_h264_stream fc_h264_stream;

/* What a stream's encoder holds at width x height (fc_h264_encoder_memory). */
uint64_t fc_h264_stream_memory(uint32_t width, uint32_t height);

/* A stream at `quality` (1..100, PROTOCOL.md 10.7), with one reference. NULL when out of memory. */
fc_h264_stream *fc_h264_stream_create(uint32_t quality);
fc_h264_stream *fc_h264_stream_ref(fc_h264_stream *s);
/* Drops a reference; the last frees the encoder. NULL is ignored. */
void fc_h264_stream_unref(fc_h264_stream *s);

/* Encoder thread: appends the access unit of img to `out`; an IDR frame when
 * force_keyframe, when the stream has no encoder yet or img's size differs
 * from its encoder's. *keyframe says whether it is one. On failure the
 * encoder is dropped, so the next image starts afresh with an IDR. */
fc_code fc_h264_stream_encode(fc_h264_stream *s, const fc_image *img, bool force_keyframe, fc_buf *out,
                              bool *keyframe, fc_error *err);

/* Encodes img as a stream of its own: one IDR frame (a RENDER's H.264 image). */
fc_code fc_h264_encode_single(const fc_image *img, uint32_t quality, fc_buf *out, fc_error *err);

#endif
