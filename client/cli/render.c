/* render.c — `fluidcast render`: expand the inputs, read the camera path if
 * there is one, frame the whole sequence once, connect, then for each frame (read ahead on the reader thread):
 * upload, set the (orbiting) camera, render, hand the image to the writer
 * thread (which appends it to the video or writes its file); report progress;
 * finish the video whatever happened. */
#include "render.h"

#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include <unistd.h>

#include "camera_path.h"
#include "cli_connect.h"
#include "cli_read_options.h"
#include "cli_report.h"
#include "cli_settings.h"
#include "fc_error.h"
#include "fc_frame.h"
#include "fluidcast.h"
#include "progress.h"
#include "render_camera.h"
#include "render_inputs.h"
#include "render_interrupt.h"
#include "render_options.h"
#include "render_output.h"
#include "render_reader.h"
#include "cli_mesh.h"
#include "render_writer.h"
#include "snapshot_camera.h"
#include "snapshot_scene.h"
#include "up_choice.h"

typedef struct render_job {
    const fc_render_options *o;
    fc_render_inputs inputs;
    fc_camera camera;               /* before --orbit turns it; the defaults of a camera path */
    fc_camera_path path;            /* --camera-path's keyframes (count 0 without) */
    fc_settings settings;
    char **todo_paths;              /* the inputs to render (--skip-existing leaves some out) */
    uint32_t *todo;                 /* their positions in inputs */
    uint32_t todo_count;
    fc_render_output output;
    uint32_t rendered;              /* images written */
} render_job;

static int exit_for(fc_code code, int otherwise)
{
    return code == FC_ERR_USAGE ? FC_EXIT_USAGE : otherwise;
}

static double now_s(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + (double)t.tv_nsec / 1e9;
}

/* ---- before connecting: the frames, the camera, the settings ---- */

/* The view options with --eye/--target moved into the recentred frame, like the particles. */
static const fc_snapshot_options *placed_view(const fc_render_options *o, fc_snapshot_options *view)
{
    *view = o->view;
    fc_cli_recentre_point(&o->view.recentring, view->eye);
    fc_cli_recentre_point(&o->view.recentring, view->target);
    return view;
}

static int choose_view(render_job *job)
{
    const fc_render_options *o = job->o;
    fc_sequence_bounds bounds;
    fc_snapshot_options view;
    fc_frame first = {0};
    fc_up_choice up;
    fc_error err;
    fc_code code = fc_sequence_bounds_read(&job->inputs, &o->view.read, &bounds, &first, &err);
    int status = FC_EXIT_OK;
    if (code == FC_OK)
        fc_cli_print_recentring(&o->view.recentring);
    if (code != FC_OK)
        status = fc_cli_fail(FC_EXIT_INPUT, "%s", err.message);
    else if (fc_up_choose(o->view.has_up, o->view.up, &first, &up, &err) != FC_OK)
        status = fc_cli_fail(FC_EXIT_INPUT, "%s", err.message);
    else if (fc_sequence_camera(placed_view(o, &view), &bounds, &up, &job->camera, &err) != FC_OK)
        status = fc_cli_fail(FC_EXIT_USAGE, "%s", err.message);
    if (status == FC_EXIT_OK) {
        /* Completed from the first frame as snapshot completes them from its one. */
        job->settings = o->view.settings.values;
        fc_cli_choices chosen;
        fc_cli_complete_settings(&job->settings, &first, &chosen);
        /* A fixed range for the whole sequence, so that its frames compare. */
        fc_cli_complete_color_range(&job->settings, &first, fc_cli_setting_given(&o->view.settings, "color_range"), &chosen);
        printf("render: %u frames, %s .. %s", (unsigned)job->inputs.count, job->inputs.paths[0],
               job->inputs.paths[job->inputs.count - 1]);
        if (o->camera_path)
            printf("; camera from %s (%u keyframes)\n", o->camera_path, (unsigned)job->path.count);
        else if (o->view.has_eye)
            printf("; camera from --eye/--target\n");
        else
            printf("; camera framed on the bounds of %u of them\n", (unsigned)bounds.framed);
        if (!up.given)
            printf("up %s\n", up.note);
        if (!o->camera_path && !o->view.has_eye)
            fc_snapshot_print_left_out(&bounds.box, true);
        fc_cli_print_radius(&job->settings, &chosen, "the first frame's particle spacing");
        if (chosen.color_range)
            fc_cli_print_color_range(&job->settings);
    }
    fc_frame_free(&first);
    return status;
}

/* The frames to render: all, or with --skip-existing those without an image. */
static int choose_frames(render_job *job)
{
    uint32_t n = job->inputs.count;
    job->todo = malloc(n * sizeof *job->todo);
    job->todo_paths = malloc(n * sizeof *job->todo_paths);
    if (!job->todo || !job->todo_paths)
        return fc_cli_fail(FC_EXIT_INPUT, "no memory for the list of frames");
    for (uint32_t i = 0; i < n; i++) {
        if (job->o->skip_existing && fc_render_output_exists(&job->output, job->inputs.numbers[i]))
            continue;
        job->todo[job->todo_count] = i;
        job->todo_paths[job->todo_count++] = job->inputs.paths[i];
    }
    if (job->todo_count < n)
        printf("skipping %u frames whose images exist\n", (unsigned)(n - job->todo_count));
    return FC_EXIT_OK;
}

/* ---- on the connection ---- */

static int client_failure(const render_job *job, const fc_error *err)
{
    return fc_cli_fail(fc_cli_exit_for_client_error(err->code), "%s: %s", job->o->view.server, err->message);
}

static int connect_and_set_up(render_job *job, fc_client **client)
{
    fc_snapshot_scene scene;
    fc_error err;
    if (fc_snapshot_scene_resolve(&job->o->view, &scene, &err) != FC_OK)
        return fc_cli_fail(exit_for(err.code, FC_EXIT_INPUT), "%s", err.message);
    fc_connect_options connect_options = fc_cli_connect_options("fluidcast render");
    if (fc_cli_connect(job->o->view.server, NULL, &connect_options, client, &err) != FC_OK)
        return fc_cli_fail(fc_cli_exit_for_client_error(err.code), "%s", err.message);
    if (fc_cli_meshes_send(*client, job->o->view.meshes, job->o->view.mesh_count, NULL, &job->o->view.recentring,
                           &err) != FC_OK)
        return fc_cli_fail(fc_cli_mesh_exit(err.code), "%s", err.message);
    if (fc_snapshot_scene_send(*client, &scene, &err) != FC_OK ||
        fc_client_set_settings(*client, &job->settings, &err) != FC_OK)
        return client_failure(job, &err);
    return FC_EXIT_OK;
}

/* Frame `slot` of the sequence of `count`: on the camera path at its
 * number, or turned by orbit x slot / count. */
static void frame_camera(const render_job *job, uint32_t slot, fc_camera *cam)
{
    if (job->path.count > 0) {
        fc_camera_path_at(&job->path, job->inputs.numbers[slot], &job->camera, cam);
        return;
    }
    double turn = job->o->has_orbit ? (double)job->o->orbit_deg * slot / job->inputs.count : 0.0;
    fc_orbit_camera(&job->camera, turn, cam);
}

static int output_failure(const fc_error *err)
{
    return fc_cli_fail(err->code == FC_ERR_PROTOCOL ? FC_EXIT_CONNECTION : FC_EXIT_OUTPUT, "%s", err->message);
}

/* Upload, camera, render; the image goes to the writer thread, so the next
 * frame is uploaded and rendered while it is encoded and written. */
static int render_frame(render_job *job, fc_client *client, fc_render_writer *writer, const fc_read_frame *item,
                        fc_progress *progress)
{
    uint32_t slot = job->todo[item->slot];
    fc_camera cam;
    frame_camera(job, slot, &cam);
    const fc_snapshot_options *view = &job->o->view;
    fc_render_request request = {.format = view->format, .quality = view->quality, .aov = view->aov};
    fc_upload_stats stats = {0};
    fc_image_result image = {0};
    fc_error err;
    int status = FC_EXIT_OK;
    /* Per-frame meshes (box_%04d.obj) with this frame's number, before its particles. */
    if (fc_cli_meshes_send(client, view->meshes, view->mesh_count, &job->inputs.numbers[slot], &view->recentring,
                           &err) != FC_OK)
        return fc_cli_fail(fc_cli_mesh_exit(err.code), "%s", err.message);
    if (fc_client_upload_frame(client, &item->frame, NULL, &stats, &err) != FC_OK ||
        fc_client_set_camera(client, &cam, &err) != FC_OK || fc_client_render(client, &request, &image, &err) != FC_OK)
        status = client_failure(job, &err);
    else if (fc_render_writer_put(writer, job->inputs.numbers[slot], &image, &err) != FC_OK)
        status = output_failure(&err);
    fc_image_result_free(&image);
    if (status == FC_EXIT_OK)
        fc_progress_frame(progress, job->inputs.paths[slot], item->frame.count, &stats);
    return status;
}

/* The frames go from the reader thread (files read and parsed ahead) through
 * the connection to the writer thread (images encoded and written behind). */
static int render_all(render_job *job, fc_client *client)
{
    fc_render_reader *reader;
    fc_render_writer *writer;
    fc_error err;
    if (fc_render_writer_start(&job->output, &writer, &err) != FC_OK)
        return fc_cli_fail(FC_EXIT_OUTPUT, "%s", err.message);
    if (fc_render_reader_start(job->todo_paths, job->todo_count, &job->o->view.read, &reader, &err) != FC_OK) {
        fc_render_writer_finish(writer, &job->rendered, &err);
        return fc_cli_fail(FC_EXIT_INPUT, "%s", err.message);
    }
    fc_progress progress;
    fc_progress_start(&progress, stdout, isatty(STDOUT_FILENO), job->todo_count);
    int status = FC_EXIT_OK;
    fc_read_frame item;
    while (status == FC_EXIT_OK && !fc_render_interrupted() && fc_render_reader_next(reader, &item)) {
        if (item.code != FC_OK) {
            if (progress.tty)
                putchar('\n');
            status = fc_cli_fail(FC_EXIT_INPUT, "frame %u of %u: %s", (unsigned)job->todo[item.slot] + 1,
                                 (unsigned)job->inputs.count, item.err.message);
        } else
            status = render_frame(job, client, writer, &item, &progress);
        fc_frame_free(&item.frame);
    }
    fc_render_reader_stop(reader);
    /* What was rendered is written, also after a failure or an interruption. */
    if (fc_render_writer_finish(writer, &job->rendered, &err) != FC_OK && status == FC_EXIT_OK)
        status = output_failure(&err);
    if (status == FC_EXIT_OK && progress.tty)
        putchar('\n');
    int signal_number = fc_render_interrupted();
    if (status == FC_EXIT_OK && signal_number && job->rendered < job->todo_count)
        status = fc_cli_fail(FC_RENDER_INTERRUPT_STATUS_BASE + signal_number, "interrupted after %u of %u frames",
                             (unsigned)job->rendered, (unsigned)job->todo_count);
    return status;
}

/* Whatever happened, a video is finished so that its frames play. */
static int finish_output(render_job *job, int status, double seconds)
{
    const char *out = job->o->view.output;
    bool video = job->output.video != NULL;
    fc_error err;
    if (fc_render_output_close(&job->output, &err) != FC_OK)
        return status != FC_EXIT_OK ? status : fc_cli_fail(FC_EXIT_OUTPUT, "%s", err.message);
    if (status != FC_EXIT_OK) {
        if (video)
            fprintf(stderr, "fluidcast: %s is finished with the %u frames rendered before it stopped\n", out,
                    (unsigned)job->rendered);
        return status;
    }
    printf("rendered %u frames to %s in %.2f s (%.1f fps)\n", (unsigned)job->rendered, out, seconds,
           seconds > 0 ? job->rendered / seconds : 0.0);
    return FC_EXIT_OK;
}

static int open_output(render_job *job)
{
    fc_error err;
    if (fc_render_output_open(job->o, &job->output, &err) != FC_OK)
        return fc_cli_fail(exit_for(err.code, FC_EXIT_OUTPUT), "%s", err.message);
    if (job->output.video)
        printf("video %s: %s, yuv420p, %ux%u, crf %u, %u fps\n", job->o->view.output,
               fc_video_codec_name(job->output.video), (unsigned)job->o->view.width, (unsigned)job->o->view.height,
               (unsigned)job->o->quality, (unsigned)job->o->fps);
    return FC_EXIT_OK;
}

static int render(render_job *job)
{
    fc_error err;
    if (fc_render_inputs_expand(job->o->inputs, job->o->input_count, &job->o->range, &job->inputs, &err) != FC_OK)
        return fc_cli_fail(exit_for(err.code, FC_EXIT_INPUT), "%s", err.message);
    job->output.options = job->o;
    if (job->o->camera_path && fc_camera_path_load(job->o->camera_path, &job->path, &err) != FC_OK)
        return fc_cli_fail(FC_EXIT_INPUT, "%s", err.message);
    int status = choose_view(job);
    if (status == FC_EXIT_OK)
        status = choose_frames(job);
    if (status != FC_EXIT_OK || job->todo_count == 0)
        return status;
    fc_client *client = NULL;
    double start = now_s();
    status = connect_and_set_up(job, &client);
    if (status == FC_EXIT_OK)
        status = open_output(job);
    if (status == FC_EXIT_OK) {
        fflush(stdout);
        fc_render_interrupt_install();
        status = render_all(job, client);
        status = finish_output(job, status, now_s() - start);
    }
    fc_client_close(client);
    return status;
}

int fc_render_main(int argc, char **argv)
{
    fc_render_options options;
    fc_error err;
    int status;
    if (fc_render_parse(argc, argv, &options, &err) != FC_OK)
        status = fc_cli_fail(FC_EXIT_USAGE, "%s", err.message);
    else if (options.help) {
        fc_render_print_help(stdout);
        status = FC_EXIT_OK;
    } else {
        render_job job = {.o = &options};
        status = render(&job);
        free(job.todo);
        free(job.todo_paths);
        fc_render_inputs_free(&job.inputs);
        fc_camera_path_free(&job.path);
    }
    fc_render_options_free(&options);
    return status;
}
