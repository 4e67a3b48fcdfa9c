/* scene_texture_cache.c — see scene_texture_cache.h. */
#include "gpu/scene_texture_cache.h"

#include <stdbool.h>
#include <stddef.h>

static void clear_entry(fc_scene_texture_entry *e)
{
    fc_scene_textures_destroy(e->textures);
    fc_scene_part_unref(e->background);
    fc_scene_part_unref(e->environment);
    *e = (fc_scene_texture_entry){0};
}

/* Only the cache holds it: no session or queued job can ask for it again. */
static bool held_by_cache_alone(fc_scene_part *part)
{
    return !part || atomic_load(&part->refs) == 1;
}

static void drop_orphans(fc_scene_texture_cache *c)
{
    for (int i = 0; i < FC_SCENE_TEXTURE_CACHE_SIZE; i++) {
        fc_scene_texture_entry *e = &c->entries[i];
        if (e->textures && held_by_cache_alone(e->background) && held_by_cache_alone(e->environment))
            clear_entry(e);
    }
}

static fc_scene_texture_entry *find(fc_scene_texture_cache *c, const fc_scene_part *background,
                                    const fc_scene_part *environment)
{
    for (int i = 0; i < FC_SCENE_TEXTURE_CACHE_SIZE; i++) {
        fc_scene_texture_entry *e = &c->entries[i];
        if (e->textures && e->background == background && e->environment == environment)
            return e;
    }
    return NULL;
}

/* A free entry, else the least recently used one, emptied. */
static fc_scene_texture_entry *make_room(fc_scene_texture_cache *c)
{
    fc_scene_texture_entry *oldest = &c->entries[0];
    for (int i = 0; i < FC_SCENE_TEXTURE_CACHE_SIZE; i++) {
        fc_scene_texture_entry *e = &c->entries[i];
        if (!e->textures)
            return e;
        if (e->last_used < oldest->last_used)
            oldest = e;
    }
    clear_entry(oldest);
    return oldest;
}

static const fc_image *images_of(const fc_scene_part *part)
{
    return part ? part->images : NULL;
}

fc_code fc_scene_texture_cache_get(fc_scene_texture_cache *c, fc_pipeline *pipeline, fc_scene_part *background,
                                   fc_scene_part *environment, const fc_scene_textures **out, fc_error *err)
{
    *out = NULL;
    drop_orphans(c);
    if (!background && !environment)
        return FC_OK;
    fc_scene_texture_entry *e = find(c, background, environment);
    if (!e) {
        fc_scene_textures *textures;
        fc_code code = fc_scene_textures_create(pipeline, images_of(background), images_of(environment), &textures,
                                                err);
        if (code != FC_OK)
            return code;
        e = make_room(c);
        e->textures = textures;
        e->background = background ? fc_scene_part_ref(background) : NULL;
        e->environment = environment ? fc_scene_part_ref(environment) : NULL;
    }
    e->last_used = ++c->clock;
    *out = e->textures;
    return FC_OK;
}

void fc_scene_texture_cache_free(fc_scene_texture_cache *c)
{
    for (int i = 0; i < FC_SCENE_TEXTURE_CACHE_SIZE; i++)
        clear_entry(&c->entries[i]);
    c->clock = 0;
}
