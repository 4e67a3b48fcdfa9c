/* view_options.c — parsing `fluidcast view`'s arguments (cli_args' table)
 * and its help text. */
#include "view_options.h"

#include <stdlib.h>
#include <string.h>

#include "cli_args.h"
#include "cli_read_options.h"
#include "cli_report.h"
#include "cli_values.h"
#include "fc_error.h"

#include "fc_host_port.h"

static fc_code set_server(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name, (void)err;
    ((fc_view_options *)o)->server = value;
    return FC_OK;
}

static fc_code set_session(void *o, const char *name, const char *value, fc_error *err)
{
    if (value[0] == '\0' || strlen(value) > 64)
        return fc_error_set(err, FC_ERR_USAGE, "%s needs a name of 1 to 64 bytes", name);
    ((fc_view_options *)o)->session = value;
    return FC_OK;
}

static fc_code set_size(void *o, const char *name, const char *value, fc_error *err)
{
    fc_view_options *v = o;
    return fc_cli_parse_size(name, value, &v->width, &v->height, err);
}

static fc_code set_format(void *o, const char *name, const char *value, fc_error *err)
{
    static const char *const names[] = {"raw", "jpeg", "h264", NULL};
    static const fc_image_format formats[] = {FC_FORMAT_RAW, FC_FORMAT_JPEG, FC_FORMAT_H264};
    int index;
    fc_code code = fc_cli_parse_choice(name, value, names, &index, err);
    if (code == FC_OK)
        ((fc_view_options *)o)->format = formats[index];
    return code;
}

static fc_code set_fps(void *o, const char *name, const char *value, fc_error *err)
{
    fc_view_options *v = o;
    fc_code code = fc_cli_parse_float(name, value, &v->fps, err);
    if (code == FC_OK && !(v->fps > 0.0f && v->fps <= 1000.0f))
        return fc_error_set(err, FC_ERR_USAGE, "%s must be in (0, 1000]", name);
    return code;
}

static fc_code set_no_spacemouse(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name, (void)value, (void)err;
    ((fc_view_options *)o)->no_spacemouse = true;
    return FC_OK;
}

static fc_code set_log_camera(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name, (void)value, (void)err;
    ((fc_view_options *)o)->log_camera = true;
    return FC_OK;
}

static fc_code set_test_script(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name, (void)err;
    ((fc_view_options *)o)->test_script = value;
    return FC_OK;
}

static fc_code add_file(void *o, const char *arg, fc_error *err)
{
    fc_view_options *v = o;
    if (v->file_count == FC_VIEW_MAX_FILES)
        return fc_error_set(err, FC_ERR_USAGE, "more than %u files", FC_VIEW_MAX_FILES);
    const char **grown = realloc(v->files, (v->file_count + 1) * sizeof *grown);
    if (!grown)
        return fc_error_set(err, FC_ERR_NOMEM, "out of memory");
    grown[v->file_count++] = arg;
    v->files = grown;
    return FC_OK;
}

static fc_code set_read(void *o, const char *name, const char *value, fc_error *err)
{
    return fc_cli_set_read_option(&((fc_view_options *)o)->read, name, value, err);
}

static const fc_cli_option options[] = {
    {"--dataset", true, set_read},
    {"--step", true, set_read},
    {"--select", true, set_read},
    {"--server", true, set_server},
    {"--session", true, set_session},
    {"--size", true, set_size},
    {"--fps", true, set_fps},
    {"--format", true, set_format},
    {"--no-spacemouse", false, set_no_spacemouse},
    {"--log-camera", false, set_log_camera},
    {"--test-script", true, set_test_script},
};

static fc_code take_setting(void *o, int argc, char **argv, int *i, bool *known, fc_error *err)
{
    return fc_cli_take_setting(&((fc_view_options *)o)->settings, argc, argv, i, known, err);
}

static const fc_cli_command command = {"view", options, sizeof options / sizeof options[0], add_file, take_setting};

/* A viewer is a stream: JPEG 4:2:0 by default (smaller, faster to encode); 444 for exact colour. */
static void view_settings_init(fc_cli_settings *s)
{
    fc_cli_settings_init(s);
    s->values.jpeg_subsampling = FC_JPEG_SUBSAMPLING_YUV420;
}

fc_code fc_view_parse(int argc, char **argv, fc_view_options *o, fc_error *err)
{
    memset(o, 0, sizeof *o);
    o->read.recentring = &o->recentring;
    o->server = FC_DEFAULT_SERVER;
    o->width = 960;
    o->height = 540;
    o->fps = 24.0f;
    o->format = FC_FORMAT_RAW;
    view_settings_init(&o->settings);
    fc_code code = fc_cli_parse_args(&command, argc, argv, o, &o->help, err);
    if (code != FC_OK || o->help)
        return code;
    if (fc_cli_setting_given(&o->settings, "jpeg_subsampling") && o->format != FC_FORMAT_JPEG)
        return fc_error_set(err, FC_ERR_USAGE, "--jpeg-subsampling applies to --format jpeg only");
    if (!o->session && o->file_count == 0)
        return fc_error_set(err, FC_ERR_USAGE, "view needs --session NAME or particle FILES");
    if (o->session && o->file_count > 0)
        return fc_error_set(err, FC_ERR_USAGE, "view takes --session NAME or FILES, not both");
    return FC_OK;
}

void fc_view_options_free(fc_view_options *o)
{
    free(o->files);
    o->files = NULL;
    o->file_count = 0;
}

void fc_view_print_help(FILE *to)
{
    fputs("usage: fluidcast view FILES... [options]\n"
          "       fluidcast view --session NAME [options]\n"
          "\n"
          "An interactive window (SDL2) on a fluidcastd server. With FILES, plays the\n"
          "sequence: each file is pushed to the daemon as a frame, looping. With\n"
          "--session, follows a live session as a viewer with its own camera.\n"
          "While the camera moves the daemon renders at half size; once it has been\n"
          "still for 300 ms the full-size image follows. The window title is the HUD:\n"
          "fps, server stage times and round-trip latency.\n"
          "\n"
          "options:\n"
          "  --server ADDR           HOST:PORT or unix:PATH (default " FC_DEFAULT_SERVER ")\n"
          "                          or srv:NAME, a DNS SRV name: the session's daemon by\n"
          "                          rendezvous hashing of the session name\n"
          "  --session NAME          follow this session instead of playing files\n"
          "  --size WxH              initial window size (default 960x540); the render\n"
          "                          size follows the window\n"
          "  --fps F                 playback rate of a sequence (default 24)\n"
          "  --format raw|jpeg|h264  how images travel (default raw: exact, largest); h264\n"
          "                          streams a session as video, about 1/10 of JPEG's bytes,\n"
          "                          for links slower than a LAN (docs/viewer.md)\n"
          "  --no-spacemouse         do not look for a SpaceMouse\n"
          "  --log-camera            print each camera sent to the daemon\n"
          "  --test-script SCRIPT    test hook: run ';'-separated commands (wait [S], drag DX DY,\n"
          "                          pan DX DY, dclick DX DY, shot FILE.bmp, key K, sleep MS,\n"
          "                          resize W H, rtt, quit) against the window\n"
          "  -h, --help              show this help\n"
          "\n",
          to);
    fc_cli_print_read_options_help(to, false);
    fc_cli_settings defaults;
    view_settings_init(&defaults);
    fc_cli_print_settings_help(to, &defaults.values);
    fputs("mouse:\n"
          "  left drag               orbit about the pivot (fly mode: look around)\n"
          "  left double-click       the fluid under the cursor becomes the pivot; the\n"
          "                          view recentres on it (playing files)\n"
          "  right or middle drag    pan\n"
          "  wheel                   dolly towards / away from the pivot\n"
          "keys:\n"
          "  r                       reset the camera (framed on the first frame)\n"
          "  f                       toggle orbit / fly mode\n"
          "  s                       cycle the smoothing method\n"
          "  space                   play / pause the sequence\n"
          "  n                       step to the next frame (pauses)\n"
          "  p                       screenshot: a full-size PNG rendered at the current\n"
          "                          camera, written as fluidcast-view-NNNN.png\n"
          "  q, Esc                  quit\n"
          "SpaceMouse (when one is plugged in, any time):\n"
          "  puck                    moves the camera (orbit or fly)\n"
          "  button 1 / button 2     reset / toggle orbit and fly\n"
          "\n",
          to);
    fc_cli_print_exit_codes(to);
}
