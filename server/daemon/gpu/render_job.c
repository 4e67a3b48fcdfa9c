/* render_job.c — see render_job.h. */
#include "gpu/render_job.h"

#include <stdlib.h>

fc_render_job *fc_render_job_create(fc_shared_frame *frame)
{
    fc_render_job *job = calloc(1, sizeof *job);
    if (!job)
        return NULL;
    job->frame = fc_shared_frame_ref(frame);
    for (int s = 0; s < FC_STAGE_COUNT; s++)
        job->stage_ms[s] = -1.0f;
    fc_buf_init(&job->message);
    return job;
}

void fc_render_job_free(fc_render_job *job)
{
    if (!job)
        return;
    fc_shared_frame_unref(job->frame);
    fc_h264_stream_unref(job->video);
    fc_scene_part_unref(job->background);
    fc_scene_part_unref(job->environment);
    fc_mesh_set_free(&job->meshes);
    fc_image_free(&job->image);
    fc_buf_free(&job->message);
    free(job);
}

void fc_render_job_free_list(fc_render_job *list)
{
    while (list) {
        fc_render_job *next = list->next;
        fc_render_job_free(list);
        list = next;
    }
}
