/* mesh_command.c — `fluidcast mesh`: expand the inputs, leave out the frames
 * whose mesh exists (--skip-existing), connect, send the settings, then for
 * each frame (read ahead on the reader thread) upload it, ask for its surface
 * and write the mesh file; report progress. */
#include "mesh_command.h"

#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "cli_connect.h"
#include "cli_frames.h"
#include "cli_report.h"
#include "fc_error.h"
#include "fc_frame.h"
#include "fluidcast.h"
#include "mesh_options.h"
#include "mesh_write.h"
#include "progress.h"
#include "render_inputs.h"
#include "render_reader.h"

typedef struct mesh_job {
    const fc_mesh_options *o;
    fc_render_inputs inputs;
    char **todo_paths;             /* the inputs to mesh (--skip-existing leaves some out) */
    uint32_t *todo;                /* their positions in inputs */
    uint32_t todo_count;
    uint32_t written;
} mesh_job;

static int exit_for(fc_code code, int otherwise)
{
    return code == FC_ERR_USAGE ? FC_EXIT_USAGE : otherwise;
}

/* The mesh file of input `slot`: the pattern with its number, or the one output. */
static fc_code output_path(const mesh_job *job, uint32_t slot, char *path, size_t size, fc_error *err)
{
    if (fc_is_frame_pattern(job->o->output))
        return fc_pattern_path(job->o->output, job->inputs.numbers[slot], path, size, err);
    if (snprintf(path, size, "%s", job->o->output) >= (int)size)
        return fc_error_set(err, FC_ERR_USAGE, "%s: path too long", job->o->output);
    return FC_OK;
}

static int choose_frames(mesh_job *job)
{
    uint32_t n = job->inputs.count;
    if (n > 1 && !fc_is_frame_pattern(job->o->output))
        return fc_cli_fail(FC_EXIT_USAGE, "%u inputs need an output pattern with one %%d, not -o %s", (unsigned)n,
                           job->o->output);
    job->todo = malloc(n * sizeof *job->todo);
    job->todo_paths = malloc(n * sizeof *job->todo_paths);
    if (!job->todo || !job->todo_paths)
        return fc_cli_fail(FC_EXIT_INPUT, "no memory for the list of frames");
    for (uint32_t i = 0; i < n; i++) {
        char path[4096];
        fc_error err;
        if (output_path(job, i, path, sizeof path, &err) != FC_OK)
            return fc_cli_fail(FC_EXIT_USAGE, "%s", err.message);
        if (job->o->skip_existing && access(path, F_OK) == 0)
            continue;
        job->todo[job->todo_count] = i;
        job->todo_paths[job->todo_count++] = job->inputs.paths[i];
    }
    if (job->todo_count < n)
        printf("skipping %u frames whose meshes exist\n", (unsigned)(n - job->todo_count));
    return FC_EXIT_OK;
}

static int client_failure(const mesh_job *job, const fc_error *err)
{
    return fc_cli_fail(fc_cli_exit_for_client_error(err->code), "%s: %s", job->o->server, err->message);
}

/* Upload, extract, write. */
static int mesh_frame(mesh_job *job, fc_client *client, const fc_read_frame *item, fc_progress *progress)
{
    uint32_t slot = job->todo[item->slot];
    fc_upload_stats stats = {0};
    fc_surface_mesh mesh = {0};
    char path[4096];
    fc_error err;
    int status = FC_EXIT_OK;
    if (fc_client_upload_frame(client, &item->frame, NULL, &stats, &err) != FC_OK ||
        fc_client_extract_surface(client, job->o->attributes, &mesh, NULL, &err) != FC_OK)
        status = client_failure(job, &err);
    else if (output_path(job, slot, path, sizeof path, &err) != FC_OK ||
             fc_mesh_write_file(path, &mesh, &err) != FC_OK)
        status = fc_cli_fail(exit_for(err.code, FC_EXIT_OUTPUT), "%s", err.message);
    fc_surface_mesh_free(&mesh);
    if (status == FC_EXIT_OK) {
        job->written++;
        fc_progress_frame(progress, job->inputs.paths[slot], item->frame.count, &stats);
    }
    return status;
}

static int mesh_all(mesh_job *job, fc_client *client)
{
    fc_render_reader *reader;
    fc_error err;
    if (fc_render_reader_start(job->todo_paths, job->todo_count, &job->o->read, &reader, &err) != FC_OK)
        return fc_cli_fail(FC_EXIT_INPUT, "%s", err.message);
    fc_progress progress;
    fc_progress_start(&progress, stdout, isatty(STDOUT_FILENO), job->todo_count);
    int status = FC_EXIT_OK;
    fc_read_frame item;
    while (status == FC_EXIT_OK && fc_render_reader_next(reader, &item)) {
        if (item.code != FC_OK)
            status = fc_cli_fail(FC_EXIT_INPUT, "frame %u of %u: %s", (unsigned)job->todo[item.slot] + 1,
                                 (unsigned)job->inputs.count, item.err.message);
        else
            status = mesh_frame(job, client, &item, &progress);
        fc_frame_free(&item.frame);
    }
    fc_render_reader_stop(reader);
    if (progress.tty)
        putchar('\n');
    return status;
}

static int mesh(mesh_job *job)
{
    fc_error err;
    if (fc_render_inputs_expand(job->o->inputs, job->o->input_count, &job->o->range, &job->inputs, &err) != FC_OK)
        return fc_cli_fail(exit_for(err.code, FC_EXIT_INPUT), "%s", err.message);
    int status = choose_frames(job);
    if (status != FC_EXIT_OK || job->todo_count == 0)
        return status;
    if (fc_cli_ensure_parent_dir(job->o->output, &err) != FC_OK)
        return fc_cli_fail(exit_for(err.code, FC_EXIT_OUTPUT), "%s", err.message);
    fc_client *client = NULL;
    fc_connect_options connect_options = fc_cli_connect_options("fluidcast mesh");
    if (fc_cli_connect(job->o->server, NULL, &connect_options, &client, &err) != FC_OK)
        return fc_cli_fail(fc_cli_exit_for_client_error(err.code), "%s", err.message);
    if (fc_client_set_settings(client, &job->o->settings.values, &err) != FC_OK)
        status = client_failure(job, &err);
    if (status == FC_EXIT_OK) {
        fflush(stdout);
        status = mesh_all(job, client);
    }
    if (status == FC_EXIT_OK)
        printf("meshed %u frames to %s\n", (unsigned)job->written, job->o->output);
    fc_client_close(client);
    return status;
}

int fc_mesh_main(int argc, char **argv)
{
    fc_mesh_options options;
    fc_error err;
    int status;
    if (fc_mesh_parse(argc, argv, &options, &err) != FC_OK)
        status = fc_cli_fail(FC_EXIT_USAGE, "%s", err.message);
    else if (options.help) {
        fc_mesh_print_help(stdout);
        status = FC_EXIT_OK;
    } else {
        mesh_job job = {.o = &options};
        status = mesh(&job);
        free(job.todo);
        free(job.todo_paths);
        fc_render_inputs_free(&job.inputs);
    }
    fc_mesh_options_free(&options);
    return status;
}
