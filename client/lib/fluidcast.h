/* fluidcast.h — libfluidcast, the client library simulation codes link to push
 * particle frames and cameras to a fluidcastd render daemon and get images back.
 *
 * A session looks like:
 *
 *     fc_client *c;
 *     fc_error err;
 *     if (fc_client_connect("render-host:7450", NULL, &c, &err) != FC_OK) { ... }
 *     fc_client_send_frame(c, &frame, &err);
 *     fc_client_set_camera(c, &camera, &err);
 *     fc_image_result img;
 *     fc_render_request req = { FC_FORMAT_PNG, 90, FC_AOV_COLOR };
 *     if (fc_client_render(c, &req, &img, &err) == FC_OK) { write img.data, img.size; }
 *     fc_image_result_free(&img);
 *     fc_client_close(c);
 *
 * Every call blocks until its bytes are sent (and, for connect and render, until
 * the server's reply arrived). A client is not thread-safe: use one client per
 * thread, or serialise the calls. The library keeps no global state.
 *
 * Errors are values: every function that can fail returns an fc_code and, given a
 * non-NULL fc_error*, fills it with the code and a reason. The codes mean:
 *   1..99            the server rejected a request; the code is the server's and
 *                    the message is the server's, prefixed "server: ".
 *   FC_ERR_CONNECT   the server could not be reached (name lookup, refused, timeout).
 *   FC_ERR_CLOSED    the connection was lost or the server said goodbye.
 *   FC_ERR_PROTOCOL  the server sent bytes that break the protocol.
 *   FC_ERR_IO        a socket call failed or a wait for the server timed out.
 *   FC_ERR_NOMEM     an allocation failed.
 *   FC_ERR_USAGE     the caller passed an invalid argument (NULL, malformed address).
 * After FC_ERR_CLOSED, FC_ERR_PROTOCOL or FC_ERR_IO the connection is unusable:
 * later calls return FC_ERR_CLOSED; close the client and connect again. A server
 * error (1..99) leaves the connection usable unless the server closed it. */
#ifndef FLUIDCAST_H
#define FLUIDCAST_H

#include "fluidcast_types.h"

#ifdef __cplusplus
extern "C" {
#endif

/* An open connection to one fluidcastd. Opaque; created by fc_client_connect,
 * released by fc_client_close. */
typedef struct fc_client fc_client;

/* Options for fc_client_connect. A zero-initialised struct (or NULL) means the
 * defaults given per field. */
typedef struct fc_connect_options {
    const char *client_name;      /* shown in the server's log; NULL: "libfluidcast". Truncated to 63 bytes. */
    uint32_t connect_timeout_ms;  /* bound on reaching the server and its WELCOME; 0: 10000 */
    uint32_t reply_timeout_ms;    /* longest silence tolerated while sending or waiting for a
                                     reply (a render can take seconds); 0: wait indefinitely */
} fc_connect_options;

/* What the server announced in its WELCOME. Plain data, copied out of the client. */
typedef struct fc_server_info {
    uint32_t protocol_version;    /* the protocol version in use on this connection */
    char server_version[32];      /* e.g. "fluidcastd 0.1.0", NUL-terminated */
    char renderer[128];           /* the daemon's GL_RENDERER, NUL-terminated */
    uint64_t max_particles;       /* largest frame the server accepts */
    uint32_t max_width;           /* largest image the server renders */
    uint32_t max_height;
    uint32_t max_message;         /* largest message payload, in bytes, the server reads */
} fc_server_info;

/* A rendered image as the server encoded it. `data` is owned by the result:
 * release it with fc_image_result_free. */
typedef struct fc_image_result {
    uint32_t width;
    uint32_t height;
    fc_image_format format;       /* the encoding of `data` (PNG, JPEG, EXR or RAW bytes) */
    fc_aov aov;                   /* what the image shows */
    float stage_ms[FC_STAGE_COUNT]; /* server-side duration of each stage; negative = not measured */
    uint8_t *data;                /* the encoded image bytes, exactly as received */
    size_t size;                  /* bytes in data */
} fc_image_result;

/* Connects to `host_port` — "HOST:PORT", "HOST" (port 7450), "[IPV6]:PORT" or
 * "[IPV6]" — sends HELLO and checks the WELCOME (protocol version 1). On success
 * *out is a new client the caller owns (fc_client_close releases it); on failure
 * *out is NULL. Errors: FC_ERR_USAGE for a malformed address, FC_ERR_CONNECT when
 * no address of the host accepts the connection in time, a server code (e.g.
 * FC_ERR_VERSION) when the server refuses the HELLO, FC_ERR_CLOSED /
 * FC_ERR_PROTOCOL / FC_ERR_IO when the handshake breaks. */
fc_code fc_client_connect(const char *host_port, const fc_connect_options *options,
                          fc_client **out, fc_error *err);

/* Copies what the server announced at connect time into *out. Both pointers
 * must be valid; never fails. */
void fc_client_server_info(const fc_client *client, fc_server_info *out);

/* Sends a particle frame; it replaces the previous one on the server. The server
 * answers only when it rejects the frame (non-finite values, too many particles):
 * that ERROR is reported by the next fc_client_render. The frame is not retained.
 * Errors: FC_ERR_TOO_LARGE (without sending) when the encoded frame exceeds the
 * server's message limit, FC_ERR_USAGE for an empty or NULL frame, plus the
 * connection errors. */
fc_code fc_client_send_frame(fc_client *client, const fc_frame *frame, fc_error *err);

/* Sends the camera for the following renders (image size included). Rejections
 * are reported by the next fc_client_render. */
fc_code fc_client_set_camera(fc_client *client, const fc_camera *camera, fc_error *err);

/* Sends the render settings for the following renders (fc_settings_default in
 * fc_frame.h gives a starting point). Rejections are reported by the next
 * fc_client_render. */
fc_code fc_client_set_settings(fc_client *client, const fc_settings *settings, fc_error *err);

/* Asks for an image of the current frame, camera and settings and waits for it.
 * On success *out holds the image (the caller frees it with fc_image_result_free).
 * On failure *out is empty (data NULL, size 0) and safe to free. When the server
 * rejected an earlier message of this client (a FRAME, CAMERA or SETTINGS) that
 * error is returned, since it is the cause, even if an image followed; the reply
 * to this request is consumed either way so the connection stays in step. */
fc_code fc_client_render(fc_client *client, const fc_render_request *request,
                         fc_image_result *out, fc_error *err);

/* Releases the image bytes and empties the result. Safe on an emptied result. */
void fc_image_result_free(fc_image_result *result);

/* Says GOODBYE to the server (best effort), closes the connection and frees the
 * client. NULL is ignored. */
void fc_client_close(fc_client *client);

#ifdef __cplusplus
}
#endif
#endif
