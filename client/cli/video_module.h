/* video_module.h — the interface of fluidcast-video.so (modules/video_module.c):
 * a video file of RGBA8 frames encoded with libavcodec, muxed with libavformat,
 * converted to yuv420p with libswscale. video_encoder.c opens it with
 * fc_cli_module_open (cli_module.h) when a video is written, and decides
 * which encoders a container gets; the module only drives libav. */
#ifndef FC_VIDEO_MODULE_H
#define FC_VIDEO_MODULE_H

#include <stddef.h>
#include <stdint.h>

#include "fluidcast_types.h"

#define FC_VIDEO_MODULE_FILE "fluidcast-video.so"
#define FC_VIDEO_MODULE_SYMBOL "fc_video_module_v1"
/* Raised whenever the structs below change. */
#define FC_VIDEO_MODULE_ABI 1u

typedef struct fc_video_file fc_video_file;

/* What a video file is opened with. The quality is the encoder's constant-rate
 * factor (x264's and VP9's crf); "mpeg4" maps 0..51 onto its quantiser 2..31. */
typedef struct fc_video_file_params {
    const char *path;                /* .mp4 or .webm: libavformat picks the muxer by name */
    const char *const *encoders;     /* libavcodec encoder names, best first: the first it has is used */
    size_t encoder_count;
    uint32_t width, height;          /* even */
    uint32_t fps;                    /* >= 1 */
    uint32_t quality;
} fc_video_file_params;

typedef struct fc_video_module {
    uint32_t abi;   /* FC_VIDEO_MODULE_ABI: first, checked when the module is opened */
    /* Creates the file and writes its header. FC_ERR_IO when libavcodec has none
     * of the encoders, or naming the file when it cannot be created; FC_ERR_NOMEM. */
    fc_code (*open)(const fc_video_file_params *params, fc_video_file **out, fc_error *err);
    /* The encoder in use, e.g. "libx264". */
    const char *(*codec_name)(const fc_video_file *f);
    /* Appends one frame: width * height RGBA8 pixels, rows top to bottom. */
    fc_code (*write_rgba)(fc_video_file *f, const uint8_t *rgba, fc_error *err);
    /* Flushes the encoder, writes the trailer and frees f. FC_ERR_IO when the
     * file cannot be completed. */
    fc_code (*close)(fc_video_file *f, fc_error *err);
} fc_video_module;

#endif
