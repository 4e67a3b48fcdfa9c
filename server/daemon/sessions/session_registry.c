/* session_registry.c — see session_registry.h. */
#include "sessions/session_registry.h"

#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "uploads/frame_pool.h"

struct fc_session_registry {
    fc_session **sessions;
    size_t count;
    size_t capacity;
    uint32_t max_sessions;
    fc_frame_pool *pool;
};

fc_code fc_registry_create(uint32_t max_sessions, fc_frame_pool *pool, fc_session_registry **out, fc_error *err)
{
    fc_session_registry *reg = calloc(1, sizeof *reg);
    if (!reg)
        return fc_error_set(err, FC_ERR_NOMEM, "session registry: out of memory");
    reg->max_sessions = max_sessions;
    reg->pool = pool;
    *out = reg;
    return FC_OK;
}

size_t fc_registry_count(const fc_session_registry *reg)
{
    return reg->count;
}

void fc_registry_destroy(fc_session_registry *reg)
{
    if (!reg)
        return;
    for (size_t i = 0; i < reg->count; i++)
        fc_session_destroy(reg->sessions[i]);
    free(reg->sessions);
    free(reg);
}

static fc_session *find_live(const fc_session_registry *reg, const char *name)
{
    for (size_t i = 0; i < reg->count; i++)
        if (!reg->sessions[i]->ended && strcmp(reg->sessions[i]->name, name) == 0)
            return reg->sessions[i];
    return NULL;
}

static fc_code add(fc_session_registry *reg, fc_session *s, fc_error *err)
{
    if (reg->count == reg->capacity) {
        size_t capacity = reg->capacity ? 2 * reg->capacity : 8;
        fc_session **grown = realloc(reg->sessions, capacity * sizeof *grown);
        if (!grown)
            return fc_error_set(err, FC_ERR_INTERNAL, "no memory for another session");
        reg->sessions = grown;
        reg->capacity = capacity;
    }
    reg->sessions[reg->count++] = s;
    return FC_OK;
}

fc_code fc_registry_open(fc_session_registry *reg, const char *name, fc_session **out, fc_error *err)
{
    *out = find_live(reg, name);
    if (*out)
        return FC_OK;
    if (reg->count >= reg->max_sessions)
        return fc_error_set(err, FC_ERR_LIMIT, "this server holds %u sessions already", reg->max_sessions);
    fc_session *s;
    fc_code code = fc_session_create(name, reg->pool, &s, err);
    if (code == FC_OK && (code = add(reg, s, err)) != FC_OK)
        fc_session_destroy(s);
    if (code == FC_OK)
        *out = s;
    return code;
}

void fc_registry_collect(fc_session_registry *reg)
{
    size_t kept = 0;
    for (size_t i = 0; i < reg->count; i++) {
        if (fc_session_unused(reg->sessions[i]))
            fc_session_destroy(reg->sessions[i]);
        else
            reg->sessions[kept++] = reg->sessions[i];
    }
    reg->count = kept;
}

fc_code fc_registry_list(const fc_session_registry *reg, fc_session_info **out, uint32_t *count, fc_error *err)
{
    *out = calloc(reg->count ? reg->count : 1, sizeof **out);
    *count = 0;
    if (!*out)
        return fc_error_set(err, FC_ERR_INTERNAL, "no memory to list %zu sessions", reg->count);
    for (size_t i = 0; i < reg->count; i++)
        if (!reg->sessions[i]->ended)
            fc_session_describe(reg->sessions[i], &(*out)[(*count)++]);
    return FC_OK;
}

double fc_registry_next_deadline(const fc_session_registry *reg)
{
    double next = -1.0;
    for (size_t i = 0; i < reg->count; i++) {
        double deadline = fc_chunk_assembly_next_deadline(&reg->sessions[i]->chunks);
        if (deadline >= 0.0 && (next < 0.0 || deadline < next))
            next = deadline;
    }
    return next;
}

/* The producer of a chunk whose frame failed answers that chunk with the ERROR. */
static void tell_producer(const fc_chunk_origin *origin, const fc_error *err, void *data)
{
    (void)data;
    origin->producer->ops->chunk_failed(origin->producer, origin->request_id, err);
}

void fc_registry_expire(fc_session_registry *reg, double now_ms)
{
    for (size_t i = 0; i < reg->count; i++)
        fc_chunk_assembly_expire(&reg->sessions[i]->chunks, now_ms, tell_producer, NULL);
}
