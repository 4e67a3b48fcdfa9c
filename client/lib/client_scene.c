/* client_scene.c — BACKGROUND and ENVIRONMENT: image files the server draws
 * around the fluid. Like SETTINGS, the server answers only a rejection, which
 * the next fc_client_render reports. */
#include "fluidcast.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "client_core.h"
#include "fc_error.h"
#include "fc_file.h"
#include "wire_scene.h"

static fc_code send_encoded(fc_client *c, const char *what, fc_error *err)
{
    fc_code code = fc_client_check_message_size(c, what, err);
    return code != FC_OK ? code : fc_client_send_tx(c, err);
}

fc_code fc_client_set_background_bytes(fc_client *client, const void *data, size_t size, fc_error *err)
{
    fc_code code = fc_client_check_usable(client, err);
    if (code != FC_OK)
        return code;
    if (!data && size > 0)
        return fc_error_set(err, FC_ERR_USAGE, "background of %zu bytes without data", size);
    fc_encoded_image image = {data, size};
    fc_buf_reset(&client->tx);
    code = fc_wire_write_background(&client->tx, fc_client_next_request_id(client), &image, err);
    return code != FC_OK ? code : send_encoded(client, "the background image", err);
}

fc_code fc_client_set_environment_bytes(fc_client *client, const void *const data[6], const size_t sizes[6],
                                        fc_error *err)
{
    fc_code code = fc_client_check_usable(client, err);
    if (code != FC_OK)
        return code;
    if ((data == NULL) != (sizes == NULL))
        return fc_error_set(err, FC_ERR_USAGE, "environment faces need both data and sizes (or neither)");
    fc_encoded_image faces[FC_CUBE_FACES];
    for (int i = 0; data && i < FC_CUBE_FACES; i++) {
        if (!data[i] || sizes[i] == 0)
            return fc_error_set(err, FC_ERR_USAGE, "environment face %s is empty", fc_cube_face_name(i));
        faces[i] = (fc_encoded_image){data[i], sizes[i]};
    }
    fc_buf_reset(&client->tx);
    code = fc_wire_write_environment(&client->tx, fc_client_next_request_id(client), data ? faces : NULL, err);
    return code != FC_OK ? code : send_encoded(client, "the environment faces", err);
}

/* A whole image file, refused before it is read to the end when the server's
 * message limit could never carry it. */
static fc_code read_image_file(const fc_client *client, const char *path, uint8_t **data, size_t *size,
                               fc_error *err)
{
    fc_code code = fc_read_file(path, client->info.max_message, data, size, err);
    if (code == FC_ERR_TOO_LARGE)
        return fc_error_set(err, code, "%s exceeds the server's message limit of %u bytes", path,
                            (unsigned)client->info.max_message);
    return code;
}

fc_code fc_client_set_background_file(fc_client *client, const char *path, fc_error *err)
{
    if (!path)
        return fc_client_set_background_bytes(client, NULL, 0, err);
    fc_code code = fc_client_check_usable(client, err);
    if (code != FC_OK)
        return code;
    uint8_t *data;
    size_t size;
    code = read_image_file(client, path, &data, &size, err);
    if (code != FC_OK)
        return code;
    if (size == 0)
        code = fc_error_set(err, FC_ERR_USAGE, "%s is empty, not an image", path);
    else
        code = fc_client_set_background_bytes(client, data, size, err);
    free(data);
    return code;
}

fc_code fc_client_set_environment_files(fc_client *client, const char *const paths[6], fc_error *err)
{
    if (!paths)
        return fc_client_set_environment_bytes(client, NULL, NULL, err);
    fc_code code = fc_client_check_usable(client, err);
    if (code != FC_OK)
        return code;
    uint8_t *data[FC_CUBE_FACES] = {NULL};
    const void *faces[FC_CUBE_FACES] = {NULL};
    size_t sizes[FC_CUBE_FACES] = {0};
    for (int i = 0; i < FC_CUBE_FACES && code == FC_OK; i++) {
        if (!paths[i])
            code = fc_error_set(err, FC_ERR_USAGE, "no file for environment face %s", fc_cube_face_name(i));
        else
            code = read_image_file(client, paths[i], &data[i], &sizes[i], err);
        if (code == FC_OK && sizes[i] == 0)
            code = fc_error_set(err, FC_ERR_USAGE, "%s is empty, not an image", paths[i]);
        faces[i] = data[i];
    }
    if (code == FC_OK)
        code = fc_client_set_environment_bytes(client, faces, sizes, err);
    for (int i = 0; i < FC_CUBE_FACES; i++)
        free(data[i]);
    return code;
}
