/* session.c — see session.h. */
#include "sessions/session.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "uploads/frame_pool.h"

fc_code fc_session_create(const char *name, fc_frame_pool *pool, fc_session **out, fc_error *err)
{
    fc_session *s = calloc(1, sizeof *s);
    if (!s)
        return fc_error_set(err, FC_ERR_INTERNAL, "no memory for session '%s'", name);
    fc_code code = fc_foam_track_create(&s->foam, err);
    if (code != FC_OK) {
        free(s);
        return code;
    }
    snprintf(s->name, sizeof s->name, "%s", name);
    fc_chunk_assembly_init(&s->chunks, pool);
    *out = s;
    return FC_OK;
}

void fc_session_destroy(fc_session *s)
{
    if (!s)
        return;
    fc_chunk_assembly_free(&s->chunks);
    fc_shared_frame_unref(s->latest);
    fc_foam_track_unref(s->foam);
    fc_mesh_set_free(&s->meshes);
    free(s->viewers);
    free(s);
}

void fc_session_describe(const fc_session *s, fc_session_info *out)
{
    memset(out, 0, sizeof *out);
    snprintf(out->name, sizeof out->name, "%s", s->name);
    out->producers = s->producers;
    out->viewers = (uint32_t)s->viewer_count;
    out->frames = s->sequence;
    out->last_frame = s->latest ? s->latest->number : 0;
}

bool fc_session_unused(const fc_session *s)
{
    return s->producers == 0 && s->viewer_count == 0;
}

void fc_session_add_producer(fc_session *s)
{
    s->producers++;
    s->had_producer = true;
}

static void end_session(fc_session *s)
{
    s->ended = true;
    /* Frames still waiting for chunks can never complete now. */
    fc_chunk_assembly_free(&s->chunks);
    fc_chunk_assembly_init(&s->chunks, s->chunks.pool);
    /* Backwards: a viewer told at once removes itself, shifting only the ones already told. */
    for (size_t i = s->viewer_count; i-- > 0;)
        s->viewers[i]->ops->session_ended(s->viewers[i]);
}

void fc_session_remove_producer(fc_session *s, const fc_session_member *producer)
{
    fc_chunk_assembly_forget(&s->chunks, producer);
    if (s->producers > 0)
        s->producers--;
    if (s->producers == 0 && s->had_producer && !s->ended)
        end_session(s);
}

fc_code fc_session_add_viewer(fc_session *s, fc_session_member *viewer, fc_error *err)
{
    if (s->viewer_count == s->viewer_capacity) {
        size_t capacity = s->viewer_capacity ? 2 * s->viewer_capacity : 4;
        fc_session_member **grown = realloc(s->viewers, capacity * sizeof *grown);
        if (!grown)
            return fc_error_set(err, FC_ERR_INTERNAL, "no memory for another viewer of '%s'", s->name);
        s->viewers = grown;
        s->viewer_capacity = capacity;
    }
    s->viewers[s->viewer_count++] = viewer;
    return FC_OK;
}

void fc_session_remove_viewer(fc_session *s, const fc_session_member *viewer)
{
    for (size_t i = 0; i < s->viewer_count; i++) {
        if (s->viewers[i] == viewer) {
            memmove(&s->viewers[i], &s->viewers[i + 1], (s->viewer_count - i - 1) * sizeof *s->viewers);
            s->viewer_count--;
            return;
        }
    }
}

void fc_session_publish(fc_session *s, fc_shared_frame *frame)
{
    fc_shared_frame_unref(s->latest);
    s->latest = frame;
    s->sequence++;
    for (size_t i = 0; i < s->viewer_count; i++)
        s->viewers[i]->ops->new_frame(s->viewers[i]);
}
