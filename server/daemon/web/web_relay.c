/* web_relay.c — a WebSocket relayed to a daemon connection (web_relay.h). */
#include "web/web_relay.h"

#include <errno.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include "wire.h"

enum {
    /* The most of one daemon message held in the relay at a time: larger
     * messages (a full-size PNG) go out as several WebSocket fragments. */
    DOWN_CHUNK = 256 * 1024,
    /* Bytes from the page not yet taken by the daemon's socket before the
     * relay stops reading the WebSocket. */
    UP_PAUSE = 1024 * 1024
};

typedef struct web_relay {
    struct lws *ws;
    struct lws *daemon;           /* the raw descriptor's wsi; NULL once closed */
    bool daemon_gone;             /* the daemon closed its side: close the WebSocket once all is sent */
    /* daemon -> page */
    uint8_t header[FC_WIRE_HEADER_SIZE];
    size_t header_got;
    bool in_message;              /* the header was read, payload_left bytes of it are to come */
    uint64_t payload_left;
    bool chunk_first;             /* the chunk starts a message */
    uint8_t *chunk;               /* LWS_PRE + DOWN_CHUNK bytes */
    size_t chunk_len;
    /* page -> daemon */
    uint8_t *up;
    size_t up_len, up_sent, up_cap;
    uint8_t up_header[FC_WIRE_HEADER_SIZE];
    uint64_t up_message_got;      /* bytes of the page's current message */
    bool up_paused;
} web_relay;

size_t fc_web_relay_size(void)
{
    return sizeof(web_relay);
}

static const fc_web_relay_config *config_of(struct lws *wsi)
{
    return lws_context_user(lws_get_context(wsi));
}

static uint32_t le32(const uint8_t *p)
{
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

/* A connection to the daemon's relay socket, adopted into lws; false when the
 * daemon does not take it (it stops, or its backlog is full). */
static bool connect_daemon(web_relay *r, struct lws *ws)
{
    const fc_web_relay_config *config = config_of(ws);
    struct sockaddr_un addr = {.sun_family = AF_UNIX};
    snprintf(addr.sun_path, sizeof addr.sun_path, "%s", config->relay_path);
    int fd = socket(AF_UNIX, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    if (fd < 0 || connect(fd, (const struct sockaddr *)&addr, sizeof addr) != 0) {
        fc_log_write(config->log, FC_LOG_WARN, "web: cannot reach the daemon's relay socket: %s", strerror(errno));
        if (fd >= 0)
            close(fd);
        return false;
    }
    lws_adopt_desc_t desc = {
        .vh = lws_get_vhost(ws),
        .type = LWS_ADOPT_RAW_FILE_DESC,
        .fd.filefd = fd,
        .vh_prot_name = FC_WEB_RELAY_PROTOCOL,
        .opaque = r,
    };
    r->daemon = lws_adopt_descriptor_vhost_via_info(&desc);   /* closes fd on failure */
    return r->daemon != NULL;
}

static bool open_relay(web_relay *r, struct lws *ws)
{
    memset(r, 0, sizeof *r);
    r->ws = ws;
    r->chunk = malloc(LWS_PRE + DOWN_CHUNK);
    return r->chunk && connect_daemon(r, ws);
}

/* The WebSocket went away: the daemon's connection follows (the daemon sees
 * EOF and ends the conversation as for any client that left). */
static void close_relay(web_relay *r)
{
    if (r->daemon) {
        lws_set_opaque_user_data(r->daemon, NULL);
        lws_set_timeout(r->daemon, PENDING_TIMEOUT_KILLED_BY_PARENT, LWS_TO_KILL_ASYNC);
        r->daemon = NULL;
    }
    free(r->chunk);
    free(r->up);
    r->chunk = r->up = NULL;
}

/* Writes what the page sent and the daemon's socket takes now; false when the
 * daemon's side failed. */
static bool flush_up(web_relay *r)
{
    while (r->daemon && r->up_sent < r->up_len) {
        ssize_t n = write(lws_get_socket_fd(r->daemon), r->up + r->up_sent, r->up_len - r->up_sent);
        if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)) {
            lws_callback_on_writable(r->daemon);
            return true;
        }
        if (n <= 0)
            return false;
        r->up_sent += (size_t)n;
    }
    r->up_len = r->up_sent = 0;
    if (r->up_paused) {
        r->up_paused = false;
        lws_rx_flow_control(r->ws, 1);
    }
    return true;
}

static bool append_up(web_relay *r, const uint8_t *data, size_t len)
{
    if (r->up_len + len > r->up_cap) {
        size_t cap = r->up_cap ? r->up_cap : 4096;
        while (cap < r->up_len + len)
            cap *= 2;
        uint8_t *grown = realloc(r->up, cap);
        if (!grown)
            return false;
        r->up = grown;
        r->up_cap = cap;
    }
    memcpy(r->up + r->up_len, data, len);
    r->up_len += len;
    return true;
}

/* Holds the page to the mapping: a WebSocket message is one whole protocol
 * message, its header's length naming exactly the bytes that follow. */
static bool check_up_framing(web_relay *r, struct lws *ws, const uint8_t *data, size_t len)
{
    if (lws_is_first_fragment(ws))
        r->up_message_got = 0;
    for (size_t i = 0; i < len && r->up_message_got + i < FC_WIRE_HEADER_SIZE; i++)
        r->up_header[r->up_message_got + i] = data[i];
    r->up_message_got += len;
    if (!lws_is_final_fragment(ws) || lws_remaining_packet_payload(ws))
        return true;
    return r->up_message_got >= FC_WIRE_HEADER_SIZE &&
           r->up_message_got == FC_WIRE_HEADER_SIZE + (uint64_t)le32(r->up_header + 12);
}

static int on_receive(web_relay *r, struct lws *ws, const uint8_t *data, size_t len)
{
    if (lws_frame_is_binary(ws) == 0 || !check_up_framing(r, ws, data, len)) {
        static const char reason[] = "each WebSocket message must be one binary protocol message";
        lws_close_reason(ws, LWS_CLOSE_STATUS_PROTOCOL_ERR, (unsigned char *)reason, sizeof reason - 1);
        return -1;
    }
    if (!append_up(r, data, len) || !flush_up(r))
        return -1;
    if (r->up_len - r->up_sent > UP_PAUSE && !r->up_paused) {
        r->up_paused = true;
        lws_rx_flow_control(ws, 0);
    }
    return 0;
}

/* Sends the chunk the daemon side filled as a fragment of its message. */
static int on_ws_writeable(web_relay *r, struct lws *ws)
{
    if (r->chunk_len) {
        bool last = r->payload_left == 0;
        int flags = r->chunk_first ? LWS_WRITE_BINARY : LWS_WRITE_CONTINUATION;
        if (!last)
            flags |= LWS_WRITE_NO_FIN;
        if (lws_write(ws, r->chunk + LWS_PRE, r->chunk_len, (enum lws_write_protocol)flags) < (int)r->chunk_len)
            return -1;
        r->chunk_len = 0;
        r->chunk_first = false;
        if (last)
            r->in_message = false;
        if (r->daemon)
            lws_rx_flow_control(r->daemon, 1);
    }
    if (r->daemon_gone && !r->chunk_len) {
        lws_close_reason(ws, LWS_CLOSE_STATUS_NORMAL, (unsigned char *)"daemon closed", 13);
        return -1;
    }
    return 0;
}

int fc_web_relay_ws_callback(struct lws *wsi, enum lws_callback_reasons reason, void *user, void *in, size_t len)
{
    web_relay *r = user;
    switch (reason) {
    case LWS_CALLBACK_ESTABLISHED: {
        char peer[64] = "";
        lws_get_peer_simple(wsi, peer, sizeof peer);
        fc_log_write(config_of(wsi)->log, FC_LOG_INFO, "web: %s: WebSocket opened", peer);
        return open_relay(r, wsi) ? 0 : -1;
    }
    case LWS_CALLBACK_RECEIVE:
        return on_receive(r, wsi, in, len);
    case LWS_CALLBACK_SERVER_WRITEABLE:
        return on_ws_writeable(r, wsi);
    case LWS_CALLBACK_CLOSED:
        close_relay(r);
        return 0;
    default:
        return 0;
    }
}

/* Reads the next header or the next part of the current message's payload;
 * 0 on progress or nothing to read yet, -1 when the daemon closed or failed. */
static int read_down(web_relay *r, int fd)
{
    ssize_t n;
    if (!r->in_message) {
        n = read(fd, r->header + r->header_got, sizeof r->header - r->header_got);
        if (n > 0) {
            r->header_got += (size_t)n;
            if (r->header_got < sizeof r->header)
                return 0;
            memcpy(r->chunk + LWS_PRE, r->header, sizeof r->header);
            r->chunk_len = sizeof r->header;
            r->chunk_first = true;
            r->in_message = true;
            r->header_got = 0;
            r->payload_left = le32(r->header + 12);
            return 0;
        }
    } else {
        size_t room = DOWN_CHUNK - r->chunk_len;
        if (room > r->payload_left)
            room = (size_t)r->payload_left;
        if (room == 0)
            return 0;
        n = read(fd, r->chunk + LWS_PRE + r->chunk_len, room);
        if (n > 0) {
            r->chunk_len += (size_t)n;
            r->payload_left -= (uint64_t)n;
            return 0;
        }
    }
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR))
        return 1;
    return -1;
}

/* The daemon's side is readable: fill the chunk up to the end of the current
 * message (or as much as is there), then hand it to the WebSocket and stop
 * reading until it is sent. */
static int on_daemon_readable(web_relay *r, struct lws *daemon)
{
    int fd = lws_get_socket_fd(daemon);
    int status = 0;
    while (status == 0 && (!r->in_message || (r->chunk_len < DOWN_CHUNK && r->payload_left > 0)))
        status = read_down(r, fd);
    if (status < 0) {
        r->daemon_gone = true;
        lws_callback_on_writable(r->ws);
        return -1;
    }
    if (r->in_message && r->chunk_len) {
        lws_rx_flow_control(daemon, 0);
        lws_callback_on_writable(r->ws);
    }
    return 0;
}

int fc_web_relay_daemon_callback(struct lws *wsi, enum lws_callback_reasons reason, void *user, void *in,
                                 size_t len)
{
    (void)user;
    (void)in;
    (void)len;
    web_relay *r = lws_get_opaque_user_data(wsi);
    switch (reason) {
    case LWS_CALLBACK_RAW_RX_FILE:
        return r ? on_daemon_readable(r, wsi) : -1;
    case LWS_CALLBACK_RAW_WRITEABLE_FILE:
        return r && flush_up(r) ? 0 : -1;
    case LWS_CALLBACK_RAW_CLOSE_FILE:
        if (r) {
            r->daemon = NULL;
            r->daemon_gone = true;
            lws_callback_on_writable(r->ws);
        }
        return 0;
    default:
        return 0;
    }
}
