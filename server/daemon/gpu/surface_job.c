/* surface_job.c — see surface_job.h. */
#include "gpu/surface_job.h"

#include <stdlib.h>

#include "fc_error.h"
#include "monotonic.h"
#include "render/surface_extract.h"
#include "wire_surface.h"

/* Drops the attribute arrays the client did not ask for. */
static void keep_attributes(fc_surface_mesh *mesh, uint32_t wanted)
{
    struct { uint32_t bit; void **array; } arrays[] = {
        {FC_SURFACE_SPEED, (void **)&mesh->speed}, {FC_SURFACE_DENSITY, (void **)&mesh->density},
        {FC_SURFACE_VELOCITY, (void **)&mesh->velocity}, {FC_SURFACE_ID, (void **)&mesh->id}};
    for (size_t i = 0; i < sizeof arrays / sizeof arrays[0]; i++)
        if (!(wanted & arrays[i].bit)) {
            free(*arrays[i].array);
            *arrays[i].array = NULL;
        }
    mesh->attributes &= wanted;
}

static fc_code write_parts(fc_render_job *job, const fc_surface_mesh *mesh, float extract_ms, fc_error *err)
{
    uint32_t parts = fc_surface_part_count(
        fc_surface_body_size(mesh->vertex_count, mesh->triangle_count, mesh->attributes));
    fc_code code = FC_OK;
    for (uint32_t i = 0; i < parts && code == FC_OK; i++)
        code = fc_wire_write_surface_part(&job->message, job->request_id, mesh, extract_ms, i, err);
    if (code != FC_OK)
        fc_buf_reset(&job->message);
    return code;
}

fc_code fc_surface_job_run(fc_pipeline *pipeline, fc_render_job *job, float radius, fc_error *err)
{
    fc_settings settings = job->settings;
    settings.radius = radius;
    fc_surface_mesh mesh = {0};
    double start = fc_monotonic_ms();
    fc_code code = fc_surface_extract(pipeline, &job->frame->frame, &settings, &mesh, err);
    float extract_ms = (float)(fc_monotonic_ms() - start);
    if (code == FC_OK) {
        keep_attributes(&mesh, job->surface_attributes);
        code = write_parts(job, &mesh, extract_ms, err);
    }
    fc_surface_mesh_free(&mesh);
    return code;
}
