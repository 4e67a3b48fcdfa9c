/* watch.c — `fluidcast watch`: subscribe to a session, then print (and
 * optionally write) each image until --count images or the session's end. */
#include "watch.h"

#include <errno.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>

#include "cli_connect.h"
#include "cli_args.h"
#include "cli_frames.h"
#include "cli_report.h"
#include "cli_values.h"
#include "fc_error.h"
#include "fluidcast.h"
#include "output_file.h"

#include "fc_host_port.h"

typedef struct watch_options {
    bool help;
    const char *server;
    const char *session;
    const char *out_dir;          /* NULL: count and print only */
    uint32_t count;               /* 0: until the session ends */
    fc_image_format format;
    bool has_quality;
    uint32_t quality;
    uint32_t width, height;
} watch_options;

/* What the run saw, for the summary line. */
typedef struct watch_totals {
    uint32_t images;
    uint64_t missed;
    double latency_sum_ms;
} watch_totals;

static fc_code set_server(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name, (void)err;
    ((watch_options *)o)->server = value;
    return FC_OK;
}

static fc_code set_session(void *o, const char *name, const char *value, fc_error *err)
{
    if (value[0] == '\0' || strlen(value) > 64)
        return fc_error_set(err, FC_ERR_USAGE, "%s needs a name of 1 to 64 bytes", name);
    ((watch_options *)o)->session = value;
    return FC_OK;
}

static fc_code set_out_dir(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name, (void)err;
    ((watch_options *)o)->out_dir = value;
    return FC_OK;
}

static fc_code set_count(void *o, const char *name, const char *value, fc_error *err)
{
    return fc_cli_parse_uint(name, value, 1, UINT32_MAX, &((watch_options *)o)->count, err);
}

static fc_code set_format(void *o, const char *name, const char *value, fc_error *err)
{
    return fc_cli_parse_format(name, value, &((watch_options *)o)->format, err);
}

static fc_code set_quality(void *o, const char *name, const char *value, fc_error *err)
{
    watch_options *w = o;
    w->has_quality = true;
    return fc_cli_parse_uint(name, value, 1, 100, &w->quality, err);
}

static fc_code set_size(void *o, const char *name, const char *value, fc_error *err)
{
    watch_options *w = o;
    return fc_cli_parse_size(name, value, &w->width, &w->height, err);
}

static const fc_cli_option options[] = {
    {"--server", true, set_server}, {"--session", true, set_session}, {"--out-dir", true, set_out_dir},
    {"--count", true, set_count},   {"--format", true, set_format},   {"--quality", true, set_quality},
    {"--size", true, set_size},
};

static const fc_cli_command command = {"watch", options, sizeof options / sizeof options[0], NULL, NULL};

static fc_code parse(int argc, char **argv, watch_options *o, fc_error *err)
{
    memset(o, 0, sizeof *o);
    o->server = FC_DEFAULT_SERVER;
    o->format = FC_FORMAT_PNG;
    o->quality = 90;
    o->width = 640;
    o->height = 360;
    fc_code code = fc_cli_parse_args(&command, argc, argv, o, &o->help, err);
    if (code != FC_OK || o->help)
        return code;
    if (!o->session)
        return fc_error_set(err, FC_ERR_USAGE, "watch needs --session NAME");
    if (o->has_quality && o->format != FC_FORMAT_JPEG && o->format != FC_FORMAT_H264)
        return fc_error_set(err, FC_ERR_USAGE, "--quality applies to --format jpg and h264 only");
    return FC_OK;
}

static void print_help(FILE *to)
{
    fputs("usage: fluidcast watch --session NAME [options]\n"
          "\n"
          "Subscribes to a session on a fluidcastd server and receives every frame its\n"
          "producer publishes, rendered for this viewer; prints one line per image (frame\n"
          "number, size, frames missed, server latency) and exits after --count images or\n"
          "when the producer ends the session. A viewer that falls behind gets the newest\n"
          "frame and is told how many it missed. With --format jpg or h264 a lossless PNG\n"
          "of the last frame follows once the stream pauses.\n"
          "\n"
          "--format h264 receives the images as one H.264 video stream (a tenth of JPEG's\n"
          "bytes or less); with --out-dir its access units go, in order, into one raw\n"
          "Annex B file, DIR/NAME.h264, that ffplay or ffmpeg reads (ffmpeg -i NAME.h264\n"
          "-c copy NAME.mp4 remuxes it); the PNG refreshes go next to it as usual.\n"
          "\n"
          "options:\n"
          "  --session NAME          the session to watch (required)\n"
          "  --server ADDR           HOST:PORT or unix:PATH (default " FC_DEFAULT_SERVER ")\n"
          "                          or srv:NAME, a DNS SRV name: the session's daemon by\n"
          "                          rendezvous hashing of the session name\n"
          "  --out-dir DIR           write each image as DIR/NAME_NNNNNN.EXT (frame number);\n"
          "                          h264: the stream as DIR/NAME.h264\n"
          "  --count N               exit after N images\n"
          "  --format FMT            png (default), jpg, exr, raw or h264\n"
          "  --quality Q             JPEG or H.264 quality 1..100 (default 90)\n"
          "  --size WxH              image size, even for h264; each frame is framed\n"
          "                          automatically (default 640x360)\n"
          "  -h, --help              show this help\n"
          "\n",
          to);
    fc_cli_print_exit_codes(to);
}

static int client_failure(const watch_options *o, const fc_error *err)
{
    return fc_cli_fail(fc_cli_exit_for_client_error(err->code), "%s: %s", o->server, err->message);
}

/* The H.264 stream's file, DIR/NAME.h264: its access units back to back (Annex B). */
static int open_video(const watch_options *o, FILE **out)
{
    *out = NULL;
    if (!o->out_dir || o->format != FC_FORMAT_H264)
        return FC_EXIT_OK;
    char path[4096];
    if ((size_t)snprintf(path, sizeof path, "%s/%s.h264", o->out_dir, o->session) >= sizeof path)
        return fc_cli_fail(FC_EXIT_USAGE, "the path %s/%s.h264 is too long", o->out_dir, o->session);
    *out = fopen(path, "wb");
    return *out ? FC_EXIT_OK : fc_cli_fail(FC_EXIT_OUTPUT, "cannot write %s: %s", path, strerror(errno));
}

static int close_video(const watch_options *o, FILE *video, int status)
{
    if (video && fclose(video) != 0 && status == FC_EXIT_OK)
        return fc_cli_fail(FC_EXIT_OUTPUT, "cannot write %s/%s.h264: %s", o->out_dir, o->session, strerror(errno));
    return status;
}

static int write_image(const watch_options *o, const fc_stream_image *img, FILE *video)
{
    char path[4096];
    fc_error err;
    if (video && img->image.format == FC_FORMAT_H264) {
        if (fwrite(img->image.data, 1, img->image.size, video) != img->image.size)
            return fc_cli_fail(FC_EXIT_OUTPUT, "cannot write %s/%s.h264: %s", o->out_dir, o->session,
                               strerror(errno));
        return FC_EXIT_OK;
    }
    if (fc_cli_frame_path(path, sizeof path, o->out_dir, o->session, img->frame_number, img->image.format, &err) !=
            FC_OK ||
        fc_output_write(path, img->image.data, img->image.size, &err) != FC_OK)
        return fc_cli_fail(FC_EXIT_OUTPUT, "%s", err.message);
    return FC_EXIT_OK;
}

static void report_image(const fc_stream_image *img, watch_totals *totals)
{
    float latency = img->image.stage_ms[FC_STAGE_TOTAL];
    totals->images++;
    totals->missed += img->missed;
    totals->latency_sum_ms += latency;
    printf("image %u: frame %llu, %ux%u %s, %zu bytes, missed %u, latency %.1f ms%s%s%s\n", totals->images,
           (unsigned long long)img->frame_number, (unsigned)img->image.width, (unsigned)img->image.height,
           fc_output_format_name(img->image.format), img->image.size, (unsigned)img->missed, (double)latency,
           img->refresh ? " (lossless refresh)" : "", img->view_change ? " (new view)" : "",
           img->keyframe ? " (key frame)" : "");
    fflush(stdout);
}

/* Receives images until the count or the session's end; *ended says which. */
static int receive(fc_client *c, const watch_options *o, FILE *video, watch_totals *totals, bool *ended)
{
    *ended = false;
    while (o->count == 0 || totals->images < o->count) {
        fc_stream_image img;
        fc_error err;
        if (fc_client_next_image(c, &img, &err) != FC_OK)
            return client_failure(o, &err);
        *ended = img.ended != 0;
        int status = FC_EXIT_OK;
        if (!*ended) {
            report_image(&img, totals);
            if (o->out_dir)
                status = write_image(o, &img, video);
        }
        fc_stream_image_free(&img);
        if (status != FC_EXIT_OK || *ended)
            return status;
    }
    return FC_EXIT_OK;
}

static int watch(const watch_options *o)
{
    fc_error err;
    if (o->out_dir && fc_cli_ensure_dir(o->out_dir, &err) != FC_OK)
        return fc_cli_fail(FC_EXIT_OUTPUT, "%s", err.message);
    fc_connect_options connect_options = fc_cli_connect_options("fluidcast watch");
    fc_client *c;
    if (fc_cli_connect(o->server, o->session, &connect_options, &c, &err) != FC_OK)
        return fc_cli_fail(fc_cli_exit_for_client_error(err.code), "%s", err.message);
    fc_render_request format = {.format = o->format, .quality = o->quality, .aov = FC_AOV_COLOR};
    watch_totals totals = {0};
    bool ended = false;
    FILE *video;
    int status = open_video(o, &video);
    if (status == FC_EXIT_OK && fc_client_subscribe(c, o->session, &format, o->width, o->height, NULL, &err) != FC_OK)
        status = client_failure(o, &err);
    else if (status == FC_EXIT_OK)
        status = receive(c, o, video, &totals, &ended);
    status = close_video(o, video, status);
    if (status == FC_EXIT_OK && !ended && fc_client_leave_session(c, &err) != FC_OK)
        status = client_failure(o, &err);
    if (status == FC_EXIT_OK)
        printf("%u image(s)%s, %llu frame(s) missed, mean latency %.1f ms\n", totals.images,
               ended ? ", session ended" : "", (unsigned long long)totals.missed,
               totals.images ? totals.latency_sum_ms / totals.images : 0.0);
    fc_client_close(c);
    return status;
}

int fc_watch_main(int argc, char **argv)
{
    watch_options options;
    fc_error err;
    if (parse(argc, argv, &options, &err) != FC_OK)
        return fc_cli_fail(FC_EXIT_USAGE, "%s", err.message);
    if (options.help) {
        print_help(stdout);
        return FC_EXIT_OK;
    }
    return watch(&options);
}
