/* client_mesh.c — MESH and MESH_TRANSFORM: triangle meshes the server draws
 * with the fluid. Like SETTINGS, the server answers only a rejection, which the
 * next fc_client_render reports; what the codec can check is checked here,
 * before anything is sent. */
#include "fluidcast.h"

#include "client_core.h"
#include "fc_error.h"
#include "wire_mesh.h"

void fc_mesh_defaults(fc_mesh *mesh)
{
    *mesh = (fc_mesh){.color = {0.8f, 0.8f, 0.8f}, .opacity = 1.0f};
    fc_mesh_identity(mesh->transform);
}

/* Sends what client->tx holds, if the server's message limit lets it. */
static fc_code send_message(fc_client *c, const char *what, fc_error *err)
{
    fc_code code = fc_client_check_message_size(c, what, err);
    return code != FC_OK ? code : fc_client_send_tx(c, err);
}

fc_code fc_client_upload_mesh(fc_client *client, const fc_mesh *mesh, fc_error *err)
{
    fc_code code = fc_client_check_usable(client, err);
    if (code != FC_OK)
        return code;
    if (!mesh)
        return fc_error_set(err, FC_ERR_USAGE, "no mesh");
    fc_buf_reset(&client->tx);
    code = fc_wire_write_mesh(&client->tx, fc_client_next_request_id(client), mesh, err);
    return code != FC_OK ? code : send_message(client, "the mesh", err);
}

fc_code fc_client_remove_mesh(fc_client *client, uint32_t id, fc_error *err)
{
    fc_code code = fc_client_check_usable(client, err);
    if (code != FC_OK)
        return code;
    fc_buf_reset(&client->tx);
    code = fc_wire_write_mesh_removal(&client->tx, fc_client_next_request_id(client), id, err);
    return code != FC_OK ? code : send_message(client, "the mesh removal", err);
}

fc_code fc_client_move_meshes(fc_client *client, const fc_mesh_transform *entries, uint32_t count, fc_error *err)
{
    fc_code code = fc_client_check_usable(client, err);
    if (code != FC_OK)
        return code;
    fc_buf_reset(&client->tx);
    code = fc_wire_write_mesh_transforms(&client->tx, fc_client_next_request_id(client), entries, count, err);
    return code != FC_OK ? code : send_message(client, "the mesh transforms", err);
}
