/* client_requests.c — the requests the server answers only when it rejects them:
 * FRAME, CAMERA and SETTINGS. Their rejections surface in fc_client_render. */
#include "fluidcast.h"

#include "client_core.h"
#include "fc_error.h"

fc_code fc_client_send_frame(fc_client *client, const fc_frame *frame, fc_error *err)
{
    fc_code code = fc_client_check_usable(client, err);
    if (code != FC_OK)
        return code;
    if (!frame || frame->count == 0 || !frame->positions)
        return fc_error_set(err, FC_ERR_USAGE, "a frame needs at least one particle position");
    return fc_client_send_frame_message(client, frame, NULL, err);
}

fc_code fc_client_set_camera(fc_client *client, const fc_camera *camera, fc_error *err)
{
    fc_code code = fc_client_check_usable(client, err);
    if (code != FC_OK)
        return code;
    if (!camera)
        return fc_error_set(err, FC_ERR_USAGE, "no camera given");
    fc_buf_reset(&client->tx);
    code = fc_wire_write_camera(&client->tx, fc_client_next_request_id(client), camera, err);
    return code != FC_OK ? code : fc_client_send_tx(client, err);
}

fc_code fc_client_set_settings(fc_client *client, const fc_settings *settings, fc_error *err)
{
    fc_code code = fc_client_check_usable(client, err);
    if (code != FC_OK)
        return code;
    if (!settings)
        return fc_error_set(err, FC_ERR_USAGE, "no settings given");
    fc_buf_reset(&client->tx);
    code = fc_wire_write_settings(&client->tx, fc_client_next_request_id(client), settings, err);
    return code != FC_OK ? code : fc_client_send_tx(client, err);
}
