/* video_encoder.h — a video file of RGBA8 frames, encoded with libavcodec and
 * muxed with libavformat: .mp4 as H.264 (libx264) or, where libavcodec was
 * built without it, MPEG-4 part 2; .webm as VP9 (libvpx-vp9). yuv420p at a
 * constant frame rate; the quality is a constant-rate factor. libav itself is
 * in fluidcast-video.so, which fc_video_open loads (cli_module.h). */
#ifndef FC_VIDEO_ENCODER_H
#define FC_VIDEO_ENCODER_H

#include <stdbool.h>
#include <stdint.h>

#include "fluidcast_types.h"

typedef struct fc_video_encoder fc_video_encoder;

/* The video container a path names: .mp4 or .webm (case-insensitive). */
bool fc_video_is_video_path(const char *path);

/* Default and largest constant-rate factor of the codec a path would use
 * (x264 23 of 51, VP9 32 of 63; the MPEG-4 fallback maps 0..51 onto its
 * quantiser 2..31). Lower is better and larger. */
uint32_t fc_video_default_quality(const char *path);
uint32_t fc_video_max_quality(const char *path);

typedef struct fc_video_params {
    uint32_t width, height;   /* even: yuv420p halves the chroma */
    uint32_t fps;             /* frames per second, >= 1 */
    uint32_t quality;         /* constant-rate factor, see above */
} fc_video_params;

/* Creates the file and writes its header. FC_ERR_USAGE for an odd size or a
 * path that is not .mp4/.webm; FC_ERR_IO when fluidcast-video.so cannot be
 * loaded (cli_module.h: the message names it and says why), when libavcodec
 * has none of the path's encoders, or naming the file when it cannot be
 * created. */
fc_code fc_video_open(const char *path, const fc_video_params *params, fc_video_encoder **out, fc_error *err);

/* The libavcodec encoder in use, e.g. "libx264". */
const char *fc_video_codec_name(const fc_video_encoder *v);

/* Appends one frame: width * height RGBA8 pixels, rows top to bottom. */
fc_code fc_video_write_rgba(fc_video_encoder *v, const uint8_t *rgba, fc_error *err);

/* Flushes the encoder, writes the trailer (so whatever was written plays) and
 * frees the encoder; NULL is ignored. FC_ERR_IO when the file cannot be
 * completed. */
fc_code fc_video_close(fc_video_encoder *v, fc_error *err);

#endif
