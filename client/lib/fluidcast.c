/* fluidcast.c — connecting (HELLO/WELCOME), server info and closing. */
#include "fluidcast.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "client_core.h"
#include "fc_error.h"
#include "fc_host_port.h"
#include "socket_io.h"
#include "srv_candidates.h"
#include "tls_client.h"
#include "wire_session.h"
#include "wire_surface.h"

#define DEFAULT_CLIENT_NAME "libfluidcast"
#define DEFAULT_CONNECT_TIMEOUT_MS 10000u
/* WELCOME and ERROR are a few hundred bytes; nothing larger is expected before
 * the server has announced its limits. */
#define HANDSHAKE_MAX_REPLY (64u * 1024u)
/* Room for container headers and metadata on top of the largest pixel data. */
#define IMAGE_OVERHEAD (1u << 20)

/* The largest IMAGE the announced limits allow: RGBA float32 (16 bytes a pixel,
 * the widest encoding) of the largest image, plus overhead. Bounding replies this
 * way keeps a corrupt length from making the client allocate gigabytes. */
/* The largest reply: an IMAGE at the largest size (PROTOCOL.md 6.1), or a
 * SURFACE_PART (13.2) when images are limited to less. */
static uint32_t max_reply(const fc_limits *limits)
{
    uint64_t bytes = (uint64_t)limits->max_width * limits->max_height * 16u + IMAGE_OVERHEAD;
    const uint64_t surface_part = FC_SURFACE_PART_FIXED_SIZE + FC_SURFACE_PART_DATA_MAX;
    if (bytes < surface_part)
        bytes = surface_part;
    return bytes > UINT32_MAX ? UINT32_MAX : (uint32_t)bytes;
}

static void copy_server_info(const fc_welcome *w, fc_server_info *info)
{
    memset(info, 0, sizeof *info);
    info->protocol_version = w->version;
    memcpy(info->server_version, w->server_version, sizeof info->server_version);
    info->server_version[sizeof info->server_version - 1] = '\0';
    memcpy(info->renderer, w->renderer, sizeof info->renderer);
    info->renderer[sizeof info->renderer - 1] = '\0';
    info->max_particles = w->limits.max_particles;
    info->max_width = w->limits.max_width;
    info->max_height = w->limits.max_height;
    info->max_message = w->limits.max_message;
    info->capabilities = w->capabilities;
    memcpy(info->device, w->device, sizeof info->device);
    info->device[sizeof info->device - 1] = '\0';
}

static fc_code send_hello(fc_client *c, const char *client_name, const char *token, fc_error *err)
{
    fc_hello hello;
    memset(&hello, 0, sizeof hello);
    hello.version_min = FC_PROTOCOL_VERSION;
    hello.version_max = FC_PROTOCOL_VERSION;
    hello.capabilities = FC_CAPS_ALL;
    snprintf(hello.client_name, sizeof hello.client_name, "%s", client_name);
    /* A cut token would only fail later with a misleading UNAUTHORIZED. */
    if (token && strlen(token) > FC_HELLO_TOKEN_MAX)
        return fc_error_set(err, FC_ERR_USAGE, "the token is longer than %d bytes", FC_HELLO_TOKEN_MAX);
    snprintf(hello.token, sizeof hello.token, "%s", token ? token : "");
    fc_buf_reset(&c->tx);
    fc_code code = fc_wire_write_hello(&c->tx, fc_client_next_request_id(c), &hello, err);
    return code != FC_OK ? code : fc_client_send_tx(c, err);
}

static fc_code receive_welcome(fc_client *c, fc_error *err)
{
    fc_msg_header header;
    fc_code code = fc_client_receive(c, &header, err);
    if (code != FC_OK)
        return code;
    if (header.type == FC_MSG_ERROR)
        return fc_client_decode_server_error(c, err);
    if (header.type != FC_MSG_WELCOME || header.request_id != c->last_request_id)
        return fc_client_unexpected(c, &header, fc_msg_name(FC_MSG_WELCOME), err);

    fc_welcome welcome;
    fc_error why;
    if (fc_wire_read_welcome(c->rx.data, c->rx.len, &welcome, &why) != FC_OK)
        return fc_error_set(err, FC_ERR_PROTOCOL, "malformed WELCOME from the server: %s", why.message);
    if (welcome.version != FC_PROTOCOL_VERSION)
        return fc_error_set(err, FC_ERR_PROTOCOL, "the server chose protocol version %u; this client speaks %u",
                            (unsigned)welcome.version, FC_PROTOCOL_VERSION);
    copy_server_info(&welcome, &c->info);
    c->max_reply = max_reply(&welcome.limits);
    return FC_OK;
}

/* The handshakes (TLS, then HELLO/WELCOME) run under the connect timeout: a
 * server that accepts but never answers counts as unreachable in time, not as
 * a render that takes long. */
static fc_code handshake(fc_client *c, const char *host, const fc_connect_options *opt, uint32_t connect_timeout,
                         fc_error *err)
{
    const char *name = opt->client_name ? opt->client_name : DEFAULT_CLIENT_NAME;
    fc_code code = fc_socket_set_timeout(c->channel.fd, connect_timeout, err);
    if (code == FC_OK && opt->tls)
        code = fc_channel_start_tls(&c->channel, host, opt, err);
    if (code == FC_OK)
        code = send_hello(c, name, opt->token, err);
    if (code == FC_OK)
        code = receive_welcome(c, err);
    if (code == FC_OK)
        code = fc_socket_set_timeout(c->channel.fd, opt->reply_timeout_ms, err);
    return code;
}

static fc_client *client_new(void)
{
    fc_client *c = calloc(1, sizeof *c);
    if (!c)
        return NULL;
    c->channel.fd = -1;
    c->max_reply = HANDSHAKE_MAX_REPLY;
    fc_buf_init(&c->tx);
    fc_buf_init(&c->rx);
    return c;
}

/* orderly: the connection is in step and said GOODBYE (TLS then ends with close_notify). */
static void client_free(fc_client *c, bool orderly)
{
    fc_channel_close(&c->channel, orderly);
    fc_buf_free(&c->tx);
    fc_buf_free(&c->rx);
    free(c);
}

static bool is_unix_address(const char *address)
{
    return address && strncmp(address, FC_UNIX_PREFIX, strlen(FC_UNIX_PREFIX)) == 0;
}

/* "unix:PATH" is a Unix-domain socket; anything else a TCP "HOST:PORT".
 * host: the host name connected to ("" for Unix), which TLS checks. */
static fc_code open_socket(const char *address, uint32_t timeout_ms, int *fd, char host[FC_HOST_MAX],
                           fc_error *err)
{
    host[0] = '\0';
    if (is_unix_address(address))
        return fc_socket_connect_unix(address + strlen(FC_UNIX_PREFIX), fd, err);
    char port[FC_PORT_MAX];
    fc_code code = fc_host_port_parse(address, &fc_server_address_rules, host, port, err);
    return code != FC_OK ? code : fc_socket_connect(host, port, timeout_ms, fd, err);
}

/* One daemon at one plain address ("HOST:PORT", "unix:PATH"): a new client on
 * success, nothing left behind on failure. */
static fc_code connect_address(const char *address, const fc_connect_options *opt, fc_client **out,
                               fc_error *err)
{
    if (opt->tls && is_unix_address(address))
        return fc_error_set(err, FC_ERR_USAGE, "%s: TLS is for TCP addresses; a Unix socket stays in clear", address);
    fc_client *c = client_new();
    if (!c)
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for a client");
    snprintf(c->address, sizeof c->address, "%s", address ? address : "");
    uint32_t connect_timeout = opt->connect_timeout_ms ? opt->connect_timeout_ms : DEFAULT_CONNECT_TIMEOUT_MS;
    char host[FC_HOST_MAX];
    fc_code code = open_socket(address, connect_timeout, &c->channel.fd, host, err);
    if (code == FC_OK)
        code = handshake(c, host, opt, connect_timeout, err);
    if (code != FC_OK) {
        client_free(c, false);
        return code;
    }
    *out = c;
    return FC_OK;
}

/* The SRV targets in their order for this session; a target that cannot be
 * reached (FC_ERR_CONNECT) gives way to the next, so that every client of the
 * session falls back to the same daemon. Any other failure (a refused token, a
 * broken handshake) is the answer: trying elsewhere would split the session. */
static fc_code connect_srv(const char *address, const char *session, const fc_connect_options *opt,
                           fc_client **out, fc_error *err)
{
    fc_srv_target targets[FC_SRV_MAX_TARGETS];
    size_t count = 0;
    fc_code code = fc_srv_candidates(address, session, targets, &count, err);
    fc_error last;
    fc_error_clear(&last);
    for (size_t i = 0; code == FC_OK && i < count; i++) {
        char target[FC_HOST_MAX + 8];
        fc_srv_target_address(&targets[i], target, sizeof target);
        fc_code tried = connect_address(target, opt, out, &last);
        if (tried == FC_OK)
            return FC_OK;
        if (tried != FC_ERR_CONNECT) {
            if (err)
                *err = last;
            return tried;
        }
    }
    if (code != FC_OK)
        return code;
    return fc_error_set(err, FC_ERR_CONNECT, "%s: none of its %zu target(s) could be reached; the last: %s",
                        address, count, last.message);
}

fc_code fc_client_connect_session(const char *address, const char *session, const fc_connect_options *options,
                                  fc_client **out, fc_error *err)
{
    if (!out)
        return fc_error_set(err, FC_ERR_USAGE, "fc_client_connect needs somewhere to store the client");
    *out = NULL;
    fc_connect_options chosen;
    memset(&chosen, 0, sizeof chosen);
    if (options)
        chosen = *options;
    const fc_connect_options *opt = &chosen;
    if (address && strncmp(address, FC_TLS_PREFIX, strlen(FC_TLS_PREFIX)) == 0) {
        address += strlen(FC_TLS_PREFIX);
        chosen.tls = 1;
    }
    if (fc_srv_is_address(address))
        return connect_srv(address, session, opt, out, err);
    return connect_address(address, opt, out, err);
}

fc_code fc_client_connect(const char *host_port, const fc_connect_options *options,
                          fc_client **out, fc_error *err)
{
    return fc_client_connect_session(host_port, NULL, options, out, err);
}

const char *fc_client_address(const fc_client *client)
{
    return client->address;
}

void fc_client_server_info(const fc_client *client, fc_server_info *out)
{
    *out = client->info;
}

void fc_client_close(fc_client *client)
{
    if (!client)
        return;
    if (!client->broken) {
        /* Best effort: the server cleans up after a plain close as well. */
        fc_buf_reset(&client->tx);
        if (fc_wire_write_goodbye(&client->tx, fc_client_next_request_id(client), NULL) == FC_OK)
            fc_client_send_tx(client, NULL);
    }
    client_free(client, !client->broken);   /* a failed GOODBYE marked it broken */
}
