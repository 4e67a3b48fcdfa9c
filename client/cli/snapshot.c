/* snapshot.c — `fluidcast snapshot`: read the particles, choose camera and
 * settings, have the server render, write the bytes it sent. */
#include "snapshot.h"

#include <stdio.h>

#include "cli_connect.h"
#include "cli_particles.h"
#include "cli_read_options.h"
#include "cli_report.h"
#include "cli_settings.h"
#include "fc_error.h"
#include "fc_frame.h"
#include "fluidcast.h"
#include "output_file.h"
#include "snapshot_camera.h"
#include "snapshot_legend.h"
#include "snapshot_options.h"
#include "cli_mesh.h"
#include "snapshot_scene.h"
#include "up_choice.h"


static int resolve_scene(const fc_snapshot_options *o, fc_snapshot_scene *scene)
{
    fc_error err;
    if (fc_snapshot_scene_resolve(o, scene, &err) != FC_OK)
        return fc_cli_fail(err.code == FC_ERR_USAGE ? FC_EXIT_USAGE : FC_EXIT_INPUT, "%s", err.message);
    return FC_EXIT_OK;
}

static int client_failure(const char *server, const fc_error *err)
{
    return fc_cli_fail(fc_cli_exit_for_client_error(err->code), "%s: %s", server, err->message);
}

/* Connects, sends frame/camera/settings and waits for the image. */
static int render_remotely(const fc_snapshot_options *o, const fc_snapshot_scene *scene, const fc_frame *frame,
                           const fc_camera *cam, const fc_settings *settings, fc_image_result *image)
{
    fc_connect_options connect_options = fc_cli_connect_options("fluidcast snapshot");
    fc_client *client;
    fc_error err;
    /* The message of a failed connect names the host and port itself. */
    if (fc_cli_connect(o->server, NULL, &connect_options, &client, &err) != FC_OK)
        return fc_cli_fail(fc_cli_exit_for_client_error(err.code), "%s", err.message);
    fc_render_request request = { .format = o->format, .quality = o->quality, .aov = o->aov };
    int status = FC_EXIT_OK;
    /* Meshes are read here: a file that cannot be read is the input's fault. */
    const uint32_t frame_zero = 0;
    if (fc_cli_meshes_send(client, o->meshes, o->mesh_count, NULL, &o->recentring, &err) != FC_OK ||
        fc_cli_meshes_send(client, o->meshes, o->mesh_count, &frame_zero, &o->recentring, &err) != FC_OK) {
        fc_client_close(client);
        return fc_cli_fail(fc_cli_mesh_exit(err.code), "%s", err.message);
    }
    /* Rejections of the scene images, meshes, FRAME, CAMERA and SETTINGS arrive as the render's error. */
    if (fc_snapshot_scene_send(client, scene, &err) != FC_OK || fc_client_send_frame(client, frame, &err) != FC_OK ||
        fc_client_set_camera(client, cam, &err) != FC_OK ||
        fc_client_set_settings(client, settings, &err) != FC_OK ||
        fc_client_render(client, &request, image, &err) != FC_OK)
        status = client_failure(o->server, &err);
    fc_client_close(client);
    return status;
}

/* The up direction is reported like the radius: only when the CLI chose it. */
static int write_image(const fc_snapshot_options *o, const fc_image_result *image, const fc_settings *settings,
                       const fc_cli_choices *chosen, const fc_up_choice *up, const fc_framing_box *box)
{
    fc_error err;
    if (fc_output_write(o->output, image->data, image->size, &err) != FC_OK)
        return fc_cli_fail(FC_EXIT_OUTPUT, "%s", err.message);
    if (chosen->per_particle_radius)
        printf("wrote %s: %ux%u %s, %zu bytes, server %.1f ms, radius per particle\n", o->output,
               (unsigned)image->width, (unsigned)image->height, fc_output_format_name(image->format), image->size,
               (double)image->stage_ms[FC_STAGE_TOTAL]);
    else
        printf("wrote %s: %ux%u %s, %zu bytes, server %.1f ms, radius %g%s\n", o->output, (unsigned)image->width,
               (unsigned)image->height, fc_output_format_name(image->format), image->size,
               (double)image->stage_ms[FC_STAGE_TOTAL], (double)settings->radius,
               chosen->radius ? " (estimated from particle spacing)" : "");
    if (chosen->per_particle_radius)
        fc_cli_print_radius(settings, chosen, NULL);
    if (!up->given)
        printf("up %s\n", up->note);
    fc_snapshot_print_left_out(box, false);
    if (chosen->color_range)
        fc_cli_print_color_range(settings);
    return FC_EXIT_OK;
}

/* The legend is drawn here rather than by the server, which sends the fluid alone. */
static int add_legend(const fc_snapshot_options *o, const fc_settings *settings, fc_image_result *image)
{
    fc_legend_box box;
    fc_error err;
    if (fc_snapshot_add_legend(image, settings, o->quality, &box, &err) != FC_OK)
        return fc_cli_fail(FC_EXIT_OUTPUT, "legend: %s", err.message);
    printf("legend: columns %d..%d, rows %d..%d\n", box.x0, box.x1 - 1, box.y0, box.y1 - 1);
    return FC_EXIT_OK;
}

static int snapshot(const fc_snapshot_options *o, fc_frame *frame)
{
    fc_snapshot_scene scene;
    int status = resolve_scene(o, &scene);
    if (status == FC_EXIT_OK)
        status = fc_cli_load_particles(o->input, &o->read, frame);
    if (status != FC_EXIT_OK)
        return status;
    fc_cli_print_recentring(&o->recentring);
    fc_up_choice up;
    fc_camera cam;
    fc_error err;
    if (fc_up_choose(o->has_up, o->up, frame, &up, &err) != FC_OK)
        return fc_cli_fail(FC_EXIT_INPUT, "%s", err.message);
    fc_framing_box box = { 0 }; /* what the auto camera frames: the fluid, not droplets flung far from it */
    if (!o->has_eye && fc_framing_box_of(frame, &box, &err) != FC_OK)
        return fc_cli_fail(FC_EXIT_INPUT, "%s", err.message);
    fc_snapshot_options placed = *o; /* --eye/--target in the recentred frame, like the particles */
    fc_cli_recentre_point(&o->recentring, placed.eye);
    fc_cli_recentre_point(&o->recentring, placed.target);
    if (fc_snapshot_camera(&placed, &box, &up, &cam, &err) != FC_OK)
        return fc_cli_fail(FC_EXIT_USAGE, "%s", err.message);
    /* The options' settings (checked while parsing), completed from the frame so the choices can be reported. */
    fc_settings settings = o->settings.values;
    fc_cli_choices chosen;
    fc_cli_complete_settings(&settings, frame, &chosen);
    fc_cli_complete_color_range(&settings, frame, fc_cli_setting_given(&o->settings, "color_range"), &chosen);
    fc_image_result image = { 0 };
    status = render_remotely(o, &scene, frame, &cam, &settings, &image);
    if (status == FC_EXIT_OK && o->legend)
        status = add_legend(o, &settings, &image);
    if (status == FC_EXIT_OK)
        status = write_image(o, &image, &settings, &chosen, &up, &box);
    fc_image_result_free(&image);
    return status;
}

int fc_snapshot_main(int argc, char **argv)
{
    fc_snapshot_options options;
    fc_error err;
    if (fc_snapshot_parse(argc, argv, &options, &err) != FC_OK)
        return fc_cli_fail(FC_EXIT_USAGE, "%s", err.message);
    if (options.help) {
        fc_snapshot_print_help(stdout);
        return FC_EXIT_OK;
    }
    fc_frame frame = { 0 };
    int status = snapshot(&options, &frame);
    fc_frame_free(&frame);
    return status;
}
