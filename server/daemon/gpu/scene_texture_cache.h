/* scene_texture_cache.h — the GL thread's textures of client scene images.
 *
 * Making textures of large images (upload and mip chain) costs far more than a
 * render, so they are kept across renders for the last few combinations of
 * background and cube map used. The cache holds a reference to each part it
 * has textures for: a cached pointer is therefore always a live part, never a
 * new part at a reused address. Entries whose parts nobody else holds any more
 * (their connections closed or sent other images) are dropped at the next
 * lookup. GL thread only. */
#ifndef FC_DAEMON_SCENE_TEXTURE_CACHE_H
#define FC_DAEMON_SCENE_TEXTURE_CACHE_H

#include <stdint.h>

#include "render/pipeline.h"
#include "uploads/scene_uploads.h"

#define FC_SCENE_TEXTURE_CACHE_SIZE 8

typedef struct fc_scene_texture_entry {
    fc_scene_part *background;    /* a reference, or NULL */
    fc_scene_part *environment;   /* a reference, or NULL */
    fc_scene_textures *textures;  /* NULL: the entry is free */
    uint64_t last_used;
} fc_scene_texture_entry;

/* A zeroed struct is an empty cache. */
typedef struct fc_scene_texture_cache {
    fc_scene_texture_entry entries[FC_SCENE_TEXTURE_CACHE_SIZE];
    uint64_t clock;
} fc_scene_texture_cache;

/* The textures for this background and cube map (either NULL: built-in),
 * created through `pipeline` when not cached; *out NULL when both are NULL.
 * Errors of fc_scene_textures_create (e.g. FC_ERR_LIMIT beyond the GPU's
 * texture size); nothing is cached then. */
fc_code fc_scene_texture_cache_get(fc_scene_texture_cache *c, fc_pipeline *pipeline, fc_scene_part *background,
                                   fc_scene_part *environment, const fc_scene_textures **out, fc_error *err);

/* Deletes every texture (before the pipeline's context goes) and drops the references. */
void fc_scene_texture_cache_free(fc_scene_texture_cache *c);

#endif
