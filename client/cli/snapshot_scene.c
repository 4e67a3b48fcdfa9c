/* snapshot_scene.c — see snapshot_scene.h. */
#include "snapshot_scene.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "fc_error.h"

#define FACES 6

static const char *const face_stems[FACES] = {"px", "nx", "py", "ny", "pz", "nz"};
static const char *const face_extensions[] = {"png", "jpg", "jpeg", "exr"};

static fc_code check_readable(const char *option, const char *path, fc_error *err)
{
    if (access(path, R_OK) != 0)
        return fc_error_set(err, FC_ERR_IO, "%s: cannot read %s: %s", option, path, strerror(errno));
    return FC_OK;
}

static fc_code copy_path(const char *text, size_t len, char out[FC_SNAPSHOT_PATH_MAX], fc_error *err)
{
    if (len >= FC_SNAPSHOT_PATH_MAX)
        return fc_error_set(err, FC_ERR_USAGE, "--cubemap: a path of %zu bytes is too long", len);
    memcpy(out, text, len);
    out[len] = '\0';
    return FC_OK;
}

/* "A,B,C,D,E,F": six non-empty names. */
static fc_code split_face_list(const char *list, fc_snapshot_scene *scene, fc_error *err)
{
    const char *p = list;
    for (int i = 0; i < FACES; i++) {
        size_t len = strcspn(p, ",");
        bool last = i == FACES - 1;
        if (len == 0 || (last ? p[len] != '\0' : p[len] != ','))
            return fc_error_set(err, FC_ERR_USAGE,
                                "--cubemap needs six comma-separated files (+X,-X,+Y,-Y,+Z,-Z) or a directory, "
                                "not \"%s\"",
                                list);
        fc_code code = copy_path(p, len, scene->faces[i], err);
        if (code != FC_OK)
            return code;
        p += len + 1;
    }
    return FC_OK;
}

/* The first DIR/STEM.EXT that exists, for each face. */
static fc_code find_faces_in(const char *dir, fc_snapshot_scene *scene, fc_error *err)
{
    for (int i = 0; i < FACES; i++) {
        bool found = false;
        for (size_t e = 0; e < sizeof face_extensions / sizeof face_extensions[0] && !found; e++) {
            int len = snprintf(scene->faces[i], FC_SNAPSHOT_PATH_MAX, "%s/%s.%s", dir, face_stems[i],
                               face_extensions[e]);
            if (len < 0 || len >= FC_SNAPSHOT_PATH_MAX)
                return fc_error_set(err, FC_ERR_USAGE, "--cubemap: the directory name is too long");
            found = access(scene->faces[i], F_OK) == 0;
        }
        if (!found)
            return fc_error_set(err, FC_ERR_IO, "--cubemap: %s has no %s.png, .jpg, .jpeg or .exr", dir,
                                face_stems[i]);
    }
    return FC_OK;
}

fc_code fc_snapshot_scene_resolve(const fc_snapshot_options *o, fc_snapshot_scene *scene, fc_error *err)
{
    memset(scene, 0, sizeof *scene);
    scene->background = o->background;
    if (o->background) {
        fc_code code = check_readable("--background", o->background, err);
        if (code != FC_OK)
            return code;
    }
    if (!o->cubemap)
        return FC_OK;
    fc_code code = strchr(o->cubemap, ',') ? split_face_list(o->cubemap, scene, err)
                                           : find_faces_in(o->cubemap, scene, err);
    for (int i = 0; i < FACES && code == FC_OK; i++)
        code = check_readable("--cubemap", scene->faces[i], err);
    scene->has_cubemap = code == FC_OK;
    return code;
}

fc_code fc_snapshot_scene_send(fc_client *client, const fc_snapshot_scene *scene, fc_error *err)
{
    fc_code code = FC_OK;
    if (scene->background)
        code = fc_client_set_background_file(client, scene->background, err);
    if (code == FC_OK && scene->has_cubemap) {
        const char *faces[6];
        for (int i = 0; i < 6; i++)
            faces[i] = scene->faces[i];
        code = fc_client_set_environment_files(client, faces, err);
    }
    return code;
}
