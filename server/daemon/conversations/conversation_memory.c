/* conversation_memory.c — see conversation_memory.h. */
#include "conversations/conversation_memory.h"

#include "fc_error.h"
#include "sessions/session.h"

uint64_t fc_memory_of_frame(const fc_frame *frame)
{
    /* Positions always; the optional arrays as present; one float of noise
     * amplitude per particle, kept by the GL thread once it renders the frame. */
    uint64_t per_particle = 3 * sizeof(float) + sizeof(float);
    if (frame->density)
        per_particle += sizeof(float);
    if (frame->velocity)
        per_particle += 3 * sizeof(float);
    if (frame->ids)
        per_particle += sizeof(uint32_t);
    if (frame->radius)
        per_particle += sizeof(float);
    return frame->count * per_particle;
}

uint64_t fc_memory_of_scene_part(const fc_scene_part *part)
{
    uint64_t bytes = 0;
    for (uint32_t i = 0; part && i < part->count; i++)
        bytes += fc_image_size(&part->images[i]);
    return bytes;
}

uint64_t fc_memory_of_video(fc_image_format format, uint32_t width, uint32_t height)
{
    return format == FC_FORMAT_H264 ? fc_h264_stream_memory(width, height) : 0;
}

/* A viewer's stream encoder, at the size its images have now. */
static uint64_t memory_of_viewer(const fc_conversation *c)
{
    if (c->role != FC_ROLE_VIEWER)
        return 0;
    uint32_t width = c->has_camera ? c->camera.width : c->viewer.auto_width;
    uint32_t height = c->has_camera ? c->camera.height : c->viewer.auto_height;
    return fc_memory_of_video(c->viewer.request.format, width, height);
}

static uint64_t memory_of_shared(const fc_shared_frame *frame)
{
    return frame ? fc_memory_of_frame(&frame->frame) : 0;
}

static uint64_t memory_of_assembly(const fc_chunk_assembly *a)
{
    uint64_t bytes = 0;
    for (int i = 0; i < FC_ASSEMBLY_MAX_FRAMES; i++)
        for (uint32_t k = 0; a->frames[i].used && k < a->frames[i].count; k++)
            bytes += fc_memory_of_frame(&a->frames[i].parts[k].frame);
    return bytes;
}

uint64_t fc_conversation_memory_held(const fc_conversation *c)
{
    uint64_t bytes = memory_of_shared(c->frame) + fc_memory_of_scene_part(c->scene.background) +
                     fc_memory_of_scene_part(c->scene.environment) + fc_mesh_set_bytes(&c->meshes) + c->out->len +
                     memory_of_viewer(c) + c->transport_bytes;
    if (c->role == FC_ROLE_PRODUCER)
        bytes += memory_of_shared(c->session->latest) + memory_of_assembly(&c->session->chunks) +
                 fc_mesh_set_bytes(&c->session->meshes);
    return bytes;
}

fc_code fc_conversation_memory_admit(const fc_conversation *c, uint64_t released, uint64_t added, const char *what,
                                     fc_error *err)
{
    uint64_t limit = c->ctx->max_session_memory;
    uint64_t held = fc_conversation_memory_held(c);
    uint64_t kept = held > released ? held - released : 0;
    if (added <= limit && kept <= limit - added)
        return FC_OK;
    return fc_error_set(err, FC_ERR_LIMIT,
                        "%s takes %llu bytes: this connection would hold %llu, beyond its limit of %llu bytes "
                        "(max_session_memory)",
                        what, (unsigned long long)added, (unsigned long long)(kept + added),
                        (unsigned long long)limit);
}
