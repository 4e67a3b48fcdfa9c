/* stream_options.c — see stream_options.h. */
#include "stream_options.h"

#include <stdlib.h>
#include <string.h>

#include "cli_args.h"
#include "cli_read_options.h"
#include "cli_frames.h"
#include "cli_report.h"
#include "cli_values.h"
#include "fc_error.h"

#include "fc_host_port.h"

static fc_code set_server(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name, (void)err;
    ((fc_stream_options *)o)->server = value;
    return FC_OK;
}

static fc_code set_session(void *o, const char *name, const char *value, fc_error *err)
{
    if (value[0] == '\0' || strlen(value) > 64)
        return fc_error_set(err, FC_ERR_USAGE, "%s needs a name of 1 to 64 bytes", name);
    ((fc_stream_options *)o)->session = value;
    return FC_OK;
}

static fc_code set_out_dir(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name, (void)err;
    ((fc_stream_options *)o)->out_dir = value;
    return FC_OK;
}

static fc_code set_format(void *o, const char *name, const char *value, fc_error *err)
{
    return fc_cli_parse_format(name, value, &((fc_stream_options *)o)->format, err);
}

static fc_code set_quality(void *o, const char *name, const char *value, fc_error *err)
{
    fc_stream_options *s = o;
    s->has_quality = true;
    return fc_cli_parse_uint(name, value, 1, 100, &s->quality, err);
}

static fc_code set_size(void *o, const char *name, const char *value, fc_error *err)
{
    fc_stream_options *s = o;
    return fc_cli_parse_size(name, value, &s->width, &s->height, err);
}

static fc_code set_up(void *o, const char *name, const char *value, fc_error *err)
{
    fc_stream_options *s = o;
    s->has_up = true;
    return fc_cli_parse_up(name, value, s->up, err);
}

static fc_code set_zstd(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name, (void)value, (void)err;
    ((fc_stream_options *)o)->upload.encoding |= FC_UPLOAD_ZSTD;
    return FC_OK;
}

static fc_code set_quantize(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name, (void)value, (void)err;
    ((fc_stream_options *)o)->upload.encoding |= FC_UPLOAD_QUANTIZE16;
    return FC_OK;
}

static fc_code set_read(void *o, const char *name, const char *value, fc_error *err)
{
    return fc_cli_set_read_option(&((fc_stream_options *)o)->read, name, value, err);
}

static fc_code add_file(void *o, const char *arg, fc_error *err)
{
    fc_stream_options *s = o;
    if (s->file_count >= FC_STREAM_MAX_FILES)
        return fc_error_set(err, FC_ERR_USAGE, "at most %d files per stream", FC_STREAM_MAX_FILES);
    const char **grown = realloc(s->files, (s->file_count + 1) * sizeof *grown);
    if (!grown)
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for the file list");
    s->files = grown;
    s->files[s->file_count++] = arg;
    return FC_OK;
}

static const fc_cli_option options[] = {
    {"--server", true, set_server},   {"--session", true, set_session}, {"--out-dir", true, set_out_dir},
    {"--format", true, set_format},   {"--quality", true, set_quality}, {"--size", true, set_size},
    {"--up", true, set_up},           {"--zstd", false, set_zstd},      {"--quantize", false, set_quantize},
    {"--dataset", true, set_read},    {"--step", true, set_read},       {"--select", true, set_read},
};

static fc_code take_setting(void *o, int argc, char **argv, int *i, bool *known, fc_error *err)
{
    return fc_cli_take_setting(&((fc_stream_options *)o)->settings, argc, argv, i, known, err);
}

static const fc_cli_command command = {"stream", options, sizeof options / sizeof options[0], add_file,
                                       take_setting};

fc_code fc_stream_parse(int argc, char **argv, fc_stream_options *out, fc_error *err)
{
    memset(out, 0, sizeof *out);
    out->read.recentring = &out->recentring;
    out->server = FC_DEFAULT_SERVER;
    out->format = FC_FORMAT_PNG;
    out->quality = 90;
    out->width = 640;
    out->height = 360;
    fc_cli_settings_init(&out->settings);
    fc_code code = fc_cli_parse_args(&command, argc, argv, out, &out->help, err);
    if (code != FC_OK || out->help)
        return code;
    if (out->file_count == 0)
        return fc_error_set(err, FC_ERR_USAGE, "stream needs at least one particle file");
    if (out->has_quality && out->format != FC_FORMAT_JPEG)
        return fc_error_set(err, FC_ERR_USAGE, "--quality applies to --format jpg only");
    if (fc_cli_setting_given(&out->settings, "jpeg_subsampling") && out->format != FC_FORMAT_JPEG)
        return fc_error_set(err, FC_ERR_USAGE, "--jpeg-subsampling applies to --format jpg only");
    /* One image per frame, each a file: a video goes to `watch --format h264` or `render` (.mp4). */
    if (out->format == FC_FORMAT_H264)
        return fc_error_set(err, FC_ERR_USAGE,
                            "--format h264 is a viewer's video stream: use fluidcast watch --format h264, "
                            "or fluidcast render with an .mp4 output");
    return FC_OK;
}

void fc_stream_options_free(fc_stream_options *o)
{
    free(o->files);
    o->files = NULL;
    o->file_count = 0;
}

void fc_stream_print_help(FILE *to)
{
    fputs("usage: fluidcast stream FILES... [options]\n"
          "\n"
          "Pushes a sequence of particle files (any format snapshot reads), one frame each,\n"
          "to a fluidcastd server the way a simulation would: into a named session that\n"
          "`fluidcast watch` viewers follow, and/or rendered back into --out-dir. The camera\n"
          "frames the first file's particles and stays put for the whole sequence.\n"
          "\n"
          "options:\n"
          "  --server ADDR           HOST:PORT or unix:PATH (default " FC_DEFAULT_SERVER ")\n"
          "                          or srv:NAME, a DNS SRV name: the session's daemon by\n"
          "                          rendezvous hashing of the session name\n"
          "  --session NAME          publish to session NAME (1..64 bytes); viewers see every\n"
          "                          frame; the session ends when the stream does\n"
          "  --out-dir DIR           ask for each frame's image and write DIR/frame_NNNNNN.EXT\n"
          "  --format FMT            png (default), jpg, exr or raw (RGBA8 rows) for --out-dir\n"
          "  --quality Q             JPEG quality 1..100 (default 90)\n"
          "  --size WxH              image size (default 640x360)\n"
          "  --up X,Y,Z|x|y|z|-x|-y|-z\n"
          "                          world direction shown as up; default: guessed from the\n"
          "                          first file's particles (the axis with a flat, dense\n"
          "                          floor at one end), +z when none stands out; printed\n"
          "  --zstd                  compress the particle data with zstd (lossless)\n"
          "  --quantize              send positions as 16-bit offsets in each frame's bounding\n"
          "                          box: error at most box extent / 131070 per axis\n"
          "  -h, --help              show this help\n"
          "\n",
          to);
    fc_cli_print_read_options_help(to, false);
    fc_settings defaults;
    fc_settings_default(&defaults);
    fc_cli_print_settings_help(to, &defaults);
    fputs("On a terminal a progress bar shows frames, MB/s, fps and the bytes saved by\n"
          "--zstd/--quantize; otherwise one line per frame. A summary line ends the run.\n"
          "\n",
          to);
    fc_cli_print_exit_codes(to);
}
