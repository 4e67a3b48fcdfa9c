/* render_output.c — see render_output.h. */
#include "render_output.h"

#include <string.h>
#include <unistd.h>

#include "cli_frames.h"
#include "fc_error.h"
#include "output_file.h"
#include "render_inputs.h"

fc_code fc_render_output_open(const fc_render_options *o, fc_render_output *out, fc_error *err)
{
    *out = (fc_render_output){.options = o};
    if (!o->video)
        return fc_cli_ensure_parent_dir(o->view.output, err);
    const fc_video_params params = {
        .width = o->view.width, .height = o->view.height, .fps = o->fps, .quality = o->quality};
    return fc_video_open(o->view.output, &params, &out->video, err);
}

fc_code fc_render_output_path(const fc_render_output *out, uint32_t number, char *path, size_t size, fc_error *err)
{
    return fc_pattern_path(out->options->view.output, number, path, size, err);
}

bool fc_render_output_exists(const fc_render_output *out, uint32_t number)
{
    char path[4096];
    fc_error err;
    return !out->video && fc_render_output_path(out, number, path, sizeof path, &err) == FC_OK &&
           access(path, F_OK) == 0;
}

static fc_code append_to_video(fc_render_output *out, const fc_image_result *image, fc_error *err)
{
    const fc_snapshot_options *view = &out->options->view;
    if (image->width != view->width || image->height != view->height ||
        image->size != (size_t)image->width * image->height * 4)
        return fc_error_set(err, FC_ERR_PROTOCOL, "the server sent a %ux%u image of %zu bytes, not %ux%u RGBA",
                            (unsigned)image->width, (unsigned)image->height, image->size, (unsigned)view->width,
                            (unsigned)view->height);
    return fc_video_write_rgba(out->video, image->data, err);
}

fc_code fc_render_output_write(fc_render_output *out, uint32_t number, const fc_image_result *image, fc_error *err)
{
    if (out->video)
        return append_to_video(out, image, err);
    char path[4096];
    fc_code code = fc_render_output_path(out, number, path, sizeof path, err);
    return code != FC_OK ? code : fc_output_write(path, image->data, image->size, err);
}

fc_code fc_render_output_close(fc_render_output *out, fc_error *err)
{
    fc_code code = fc_video_close(out->video, err);
    out->video = NULL;
    return code;
}
