/* stream.c — `fluidcast stream`: connect, optionally publish to a session,
 * then for each file: upload the frame, optionally render it back and write
 * the image; report progress; end the session. */
#include "stream.h"

#include <stdio.h>
#include <unistd.h>

#include "cli_connect.h"
#include "cli_frames.h"
#include "cli_particles.h"
#include "cli_read_options.h"
#include "cli_report.h"
#include "cli_settings.h"
#include "fc_error.h"
#include "fc_frame.h"
#include "fluidcast.h"
#include "output_file.h"
#include "progress.h"
#include "stream_options.h"
#include "up_choice.h"
#include "upright_framing.h"

static int client_failure(const fc_stream_options *o, const fc_error *err)
{
    return fc_cli_fail(fc_cli_exit_for_client_error(err->code), "%s: %s", o->server, err->message);
}

/* Camera and settings for the whole sequence, from its first frame. A
 * guessed up is printed before the first frame's line (or progress bar). */
static int set_up_view(fc_client *c, const fc_stream_options *o, const fc_frame *first)
{
    fc_up_choice up;
    fc_error err;
    if (fc_up_choose(o->has_up, o->up, first, &up, &err) != FC_OK)
        return fc_cli_fail(FC_EXIT_INPUT, "%s", err.message);
    if (!up.given)
        printf("up %s\n", up.note);
    fc_camera cam;
    if (fc_frame_upright(first, o->width, o->height, up.up, &cam, &err) != FC_OK)
        return fc_cli_fail(FC_EXIT_INPUT, "%s", err.message);
    fc_error why;
    if (fc_camera_validate(&cam, &why) != FC_OK)
        return fc_cli_fail(FC_EXIT_USAGE, "bad camera: %s", why.message);
    fc_settings settings = o->settings.values;
    fc_cli_choices chosen;
    fc_cli_complete_settings(&settings, first, &chosen);
    fc_cli_complete_color_range(&settings, first, fc_cli_setting_given(&o->settings, "color_range"), &chosen);
    if (chosen.color_range)
        fc_cli_print_color_range(&settings);
    if (fc_client_set_camera(c, &cam, &err) != FC_OK || fc_client_set_settings(c, &settings, &err) != FC_OK)
        return client_failure(o, &err);
    return FC_EXIT_OK;
}

static int render_and_write(fc_client *c, const fc_stream_options *o, uint32_t number)
{
    fc_render_request request = {.format = o->format, .quality = o->quality, .aov = FC_AOV_COLOR};
    fc_image_result image = {0};
    fc_error err;
    char path[4096];
    int status = FC_EXIT_OK;
    if (fc_client_render(c, &request, &image, &err) != FC_OK)
        status = client_failure(o, &err);
    else if (fc_cli_frame_path(path, sizeof path, o->out_dir, "frame", number, o->format, &err) != FC_OK ||
             fc_output_write(path, image.data, image.size, &err) != FC_OK)
        status = fc_cli_fail(FC_EXIT_OUTPUT, "%s", err.message);
    fc_image_result_free(&image);
    return status;
}

/* Uploads file i and does what follows for it. */
static int push_file(fc_client *c, const fc_stream_options *o, uint32_t i, fc_progress *progress)
{
    fc_frame frame = {0};
    int status = fc_cli_load_particles(o->files[i], &o->read, &frame);
    if (status == FC_EXIT_OK && i == 0) {
        fc_cli_print_recentring(&o->recentring);
        status = set_up_view(c, o, &frame);
    }
    fc_upload_stats stats = {0};
    fc_error err;
    if (status == FC_EXIT_OK && fc_client_upload_frame(c, &frame, &o->upload, &stats, &err) != FC_OK)
        status = client_failure(o, &err);
    if (status == FC_EXIT_OK && o->out_dir)
        status = render_and_write(c, o, i + 1);
    /* Without renders nothing else would surface a rejected frame before the end. */
    if (status == FC_EXIT_OK && !o->out_dir && fc_client_poll_errors(c, &err) != FC_OK)
        status = client_failure(o, &err);
    if (status == FC_EXIT_OK)
        fc_progress_frame(progress, o->files[i], frame.count, &stats);
    fc_frame_free(&frame);
    return status;
}

static int push_all(fc_client *c, const fc_stream_options *o)
{
    fc_progress progress;
    fc_progress_start(&progress, stdout, isatty(STDOUT_FILENO), o->file_count);
    int status = FC_EXIT_OK;
    for (uint32_t i = 0; i < o->file_count && status == FC_EXIT_OK; i++)
        status = push_file(c, o, i, &progress);
    if (status == FC_EXIT_OK)
        fc_progress_finish(&progress);
    return status;
}

static int stream(const fc_stream_options *o)
{
    fc_error err;
    if (o->out_dir && fc_cli_ensure_dir(o->out_dir, &err) != FC_OK)
        return fc_cli_fail(FC_EXIT_OUTPUT, "%s", err.message);
    fc_connect_options connect_options = fc_cli_connect_options("fluidcast stream");
    fc_client *c;
    if (fc_cli_connect(o->server, o->session, &connect_options, &c, &err) != FC_OK)
        return fc_cli_fail(fc_cli_exit_for_client_error(err.code), "%s", err.message);
    int status = FC_EXIT_OK;
    if (o->session && fc_client_publish(c, o->session, NULL, &err) != FC_OK)
        status = client_failure(o, &err);
    if (status == FC_EXIT_OK)
        status = push_all(c, o);
    /* Leaving waits for the server, so a late rejection is still reported. */
    if (status == FC_EXIT_OK && o->session && fc_client_leave_session(c, &err) != FC_OK)
        status = client_failure(o, &err);
    fc_client_close(c);
    return status;
}

int fc_stream_main(int argc, char **argv)
{
    fc_stream_options options;
    fc_error err;
    int status;
    if (fc_stream_parse(argc, argv, &options, &err) != FC_OK)
        status = fc_cli_fail(FC_EXIT_USAGE, "%s", err.message);
    else if (options.help) {
        fc_stream_print_help(stdout);
        status = FC_EXIT_OK;
    } else
        status = stream(&options);
    fc_stream_options_free(&options);
    return status;
}
