/* video_encoder.c — see video_encoder.h. Which encoders a container gets and
 * the checks are here; libav itself is in fluidcast-video.so (video_module.h),
 * opened when a video is created, so no other command loads it. */
#include "video_encoder.h"

#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "cli_module.h"
#include "fc_error.h"
#include "video_module.h"

/* What each container is encoded with, best first. */
typedef struct video_codec {
    const char *encoder;      /* libavcodec encoder name */
    uint32_t default_crf, max_crf;
} video_codec;

static const video_codec mp4_codecs[] = {{"libx264", 23, 51}, {"mpeg4", 23, 51}};
static const video_codec webm_codecs[] = {{"libvpx-vp9", 32, 63}};
#define MAX_CANDIDATES 2

struct fc_video_encoder {
    fc_cli_module module;          /* fluidcast-video.so */
    const fc_video_module *video;  /* its interface */
    fc_video_file *file;
};

static const char *extension_of(const char *path)
{
    const char *dot = strrchr(path, '.');
    const char *slash = strrchr(path, '/');
    return dot && (!slash || dot > slash) ? dot : "";
}

/* The candidates for a path, or NULL when it names no video container. */
static const video_codec *codecs_for(const char *path, size_t *count)
{
    const char *ext = extension_of(path);
    if (strcasecmp(ext, ".mp4") == 0) {
        *count = sizeof mp4_codecs / sizeof mp4_codecs[0];
        return mp4_codecs;
    }
    if (strcasecmp(ext, ".webm") == 0) {
        *count = sizeof webm_codecs / sizeof webm_codecs[0];
        return webm_codecs;
    }
    *count = 0;
    return NULL;
}

bool fc_video_is_video_path(const char *path)
{
    size_t count;
    return codecs_for(path, &count) != NULL;
}

uint32_t fc_video_default_quality(const char *path)
{
    size_t count;
    const video_codec *c = codecs_for(path, &count);
    return c ? c[0].default_crf : 0;
}

uint32_t fc_video_max_quality(const char *path)
{
    size_t count;
    const video_codec *c = codecs_for(path, &count);
    return c ? c[0].max_crf : 0;
}

static fc_code check_params(const char *path, const fc_video_params *p, fc_error *err)
{
    if (!fc_video_is_video_path(path))
        return fc_error_set(err, FC_ERR_USAGE, "%s is not a video: use .mp4 or .webm", path);
    if (p->width % 2 || p->height % 2)
        return fc_error_set(err, FC_ERR_USAGE, "video needs an even width and height (yuv420p), not %ux%u",
                            (unsigned)p->width, (unsigned)p->height);
    if (p->fps < 1)
        return fc_error_set(err, FC_ERR_USAGE, "video needs at least 1 frame per second");
    return FC_OK;
}

/* The file opened through the module with path's encoders, best first. */
static fc_code open_file(fc_video_encoder *v, const char *path, const fc_video_params *params, fc_error *err)
{
    size_t count;
    const video_codec *c = codecs_for(path, &count);
    const char *names[MAX_CANDIDATES];
    for (size_t i = 0; i < count && i < MAX_CANDIDATES; i++)
        names[i] = c[i].encoder;
    const fc_video_file_params file = {.path = path,
                                       .encoders = names,
                                       .encoder_count = count < MAX_CANDIDATES ? count : MAX_CANDIDATES,
                                       .width = params->width,
                                       .height = params->height,
                                       .fps = params->fps,
                                       .quality = params->quality};
    return v->video->open(&file, &v->file, err);
}

fc_code fc_video_open(const char *path, const fc_video_params *params, fc_video_encoder **out, fc_error *err)
{
    *out = NULL;
    fc_code code = check_params(path, params, err);
    if (code != FC_OK)
        return code;
    fc_video_encoder *v = calloc(1, sizeof *v);
    if (!v)
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for the video encoder");
    code = fc_cli_module_open(FC_VIDEO_MODULE_FILE, FC_VIDEO_MODULE_SYMBOL, FC_VIDEO_MODULE_ABI, "video output",
                              &v->module, err);
    if (code == FC_OK) {
        v->video = v->module.api;
        code = open_file(v, path, params, err);
    }
    if (code != FC_OK) {
        fc_cli_module_close(&v->module);
        free(v);
        return code;
    }
    *out = v;
    return FC_OK;
}

const char *fc_video_codec_name(const fc_video_encoder *v)
{
    return v->video->codec_name(v->file);
}

fc_code fc_video_write_rgba(fc_video_encoder *v, const uint8_t *rgba, fc_error *err)
{
    return v->video->write_rgba(v->file, rgba, err);
}

fc_code fc_video_close(fc_video_encoder *v, fc_error *err)
{
    if (!v)
        return FC_OK;
    fc_code code = v->video->close(v->file, err);
    fc_cli_module_close(&v->module);
    free(v);
    return code;
}
