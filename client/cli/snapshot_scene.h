/* snapshot_scene.h — the scene image files of `fluidcast snapshot`
 * (--background, --cubemap): resolved to paths and checked readable before
 * anything is sent, so a missing file is an input error, not a server's. */
#ifndef FC_SNAPSHOT_SCENE_H
#define FC_SNAPSHOT_SCENE_H

#include <stdbool.h>

#include "fluidcast.h"
#include "fluidcast_types.h"
#include "snapshot_options.h"

#define FC_SNAPSHOT_PATH_MAX 4096

typedef struct fc_snapshot_scene {
    const char *background;                    /* NULL: the server's built-in floor and sky */
    bool has_cubemap;
    char faces[6][FC_SNAPSHOT_PATH_MAX];       /* +X, -X, +Y, -Y, +Z, -Z */
} fc_snapshot_scene;

/* From --background and --cubemap: a --cubemap value with commas is the six
 * face files in order, otherwise a directory searched for px, nx, py, ny, pz
 * and nz with the extension .png, .jpg, .jpeg or .exr (first found).
 * FC_ERR_USAGE when a list does not hold six names; FC_ERR_IO naming the file
 * (or the face missing from the directory) when one cannot be read. */
fc_code fc_snapshot_scene_resolve(const fc_snapshot_options *o, fc_snapshot_scene *scene, fc_error *err);

/* Sends the scene's images on `client` (nothing for the built-in scene).
 * They go before the frame: a rejection then names the image before a large
 * upload, and they apply to every later render either way. */
fc_code fc_snapshot_scene_send(fc_client *client, const fc_snapshot_scene *scene, fc_error *err);

#endif
