/* scene_uploads.c — a client's background and cube map, decoded on arrival. */
#include "uploads/scene_uploads.h"

#include <stdlib.h>

#include "image_decoder.h"
#include "fc_error.h"

fc_scene_part *fc_scene_part_ref(fc_scene_part *part)
{
    atomic_fetch_add(&part->refs, 1);
    return part;
}

void fc_scene_part_unref(fc_scene_part *part)
{
    if (!part || atomic_fetch_sub(&part->refs, 1) != 1)
        return;
    for (uint32_t i = 0; i < part->count; i++)
        fc_image_free(&part->images[i]);
    free(part);
}

/* A part of `count` decoded files, with one reference. *files may be freed
 * after. On failure the message names the image (`what`, and the face). */
static fc_code decode_part(const fc_encoded_image *files, uint32_t count, const char *what, fc_scene_part **out,
                           fc_error *err)
{
    fc_scene_part *part = calloc(1, sizeof *part);
    if (!part)
        return fc_error_set(err, FC_ERR_NOMEM, "%s: out of memory", what);
    atomic_init(&part->refs, 1);
    part->count = count;
    for (uint32_t i = 0; i < count; i++) {
        fc_error why;
        if (fc_decode_image_bytes(files[i].data, (size_t)files[i].size, FC_SCENE_IMAGE_MAX_SIDE, &part->images[i],
                                  &why) != FC_OK) {
            fc_scene_part_unref(part);
            if (count == 1)
                return fc_error_set(err, why.code, "%s: %s", what, why.message);
            return fc_error_set(err, why.code, "%s: face %s: %s", what, fc_cube_face_name((int)i), why.message);
        }
    }
    *out = part;
    return FC_OK;
}

/* The cube map needs six square faces alike in size and pixel type. */
static fc_code check_faces_match(const fc_image *faces, fc_error *err)
{
    for (int i = 0; i < FC_CUBE_FACES; i++) {
        const char *name = fc_cube_face_name(i);
        if (faces[i].width != faces[i].height)
            return fc_error_set(err, FC_ERR_INVALID_VALUE, "ENVIRONMENT: face %s is %ux%u, not square", name,
                                faces[i].width, faces[i].height);
        if (faces[i].width != faces[0].width)
            return fc_error_set(err, FC_ERR_INVALID_VALUE, "ENVIRONMENT: face %s is %ux%u but face +X is %ux%u",
                                name, faces[i].width, faces[i].height, faces[0].width, faces[0].height);
        if (faces[i].type != faces[0].type)
            return fc_error_set(err, FC_ERR_INVALID_VALUE,
                                "ENVIRONMENT: face %s is %s but face +X is %s: give every face the same format",
                                name, faces[i].type == FC_PIXEL_F32 ? "float" : "8-bit",
                                faces[0].type == FC_PIXEL_F32 ? "float" : "8-bit");
    }
    return FC_OK;
}

fc_code fc_scene_part_decode_background(const uint8_t *payload, size_t n, fc_scene_part **out, fc_error *err)
{
    fc_encoded_image file;
    *out = NULL;
    fc_code code = fc_wire_read_background(payload, n, &file, err);
    if (code == FC_OK && file.size > 0)
        code = decode_part(&file, 1, "BACKGROUND", out, err);
    return code;
}

fc_code fc_scene_part_decode_environment(const uint8_t *payload, size_t n, fc_scene_part **out, fc_error *err)
{
    fc_encoded_image files[FC_CUBE_FACES];
    bool has_faces;
    fc_scene_part *part = NULL;
    *out = NULL;
    fc_code code = fc_wire_read_environment(payload, n, files, &has_faces, err);
    if (code == FC_OK && has_faces)
        code = decode_part(files, FC_CUBE_FACES, "ENVIRONMENT", &part, err);
    if (code == FC_OK && part)
        code = check_faces_match(part->images, err);
    if (code != FC_OK) {
        fc_scene_part_unref(part);
        return code;
    }
    *out = part;
    return FC_OK;
}

void fc_scene_uploads_replace(fc_scene_part **slot, fc_scene_part *part)
{
    fc_scene_part_unref(*slot);
    *slot = part;
}

void fc_scene_uploads_free(fc_scene_uploads *u)
{
    fc_scene_uploads_replace(&u->background, NULL);
    fc_scene_uploads_replace(&u->environment, NULL);
}
