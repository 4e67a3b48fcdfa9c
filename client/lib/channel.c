/* channel.c — see channel.h. */
#include "channel.h"

#include <errno.h>
#include <poll.h>
#include <unistd.h>

#include "socket_io.h"
#include "tls_client.h"

fc_code fc_channel_send_all(fc_channel *ch, const uint8_t *data, size_t n, fc_error *err)
{
    if (!ch->ssl)
        return fc_socket_send_all(ch->fd, data, n, err);
    while (n > 0) {
        size_t sent = 0;
        errno = 0;
        int ret = SSL_write_ex(ch->ssl, data, n, &sent);
        if (ret != 1)
            return fc_tls_client_failure(ch->ssl, ret, "sending to", err);
        data += sent;
        n -= sent;
    }
    return FC_OK;
}

/* Over TLS each part is written on its own: every record is encrypted from
 * the part where it lies, so nothing is concatenated either way. */
fc_code fc_channel_send_parts(fc_channel *ch, struct iovec *parts, size_t count, fc_error *err)
{
    if (!ch->ssl)
        return fc_socket_send_parts(ch->fd, parts, count, err);
    for (size_t i = 0; i < count; i++) {
        fc_code code = fc_channel_send_all(ch, parts[i].iov_base, parts[i].iov_len, err);
        if (code != FC_OK)
            return code;
    }
    return FC_OK;
}

fc_code fc_channel_recv_exact(fc_channel *ch, uint8_t *data, size_t n, fc_error *err)
{
    if (!ch->ssl)
        return fc_socket_recv_exact(ch->fd, data, n, err);
    while (n > 0) {
        size_t got = 0;
        errno = 0;
        int ret = SSL_read_ex(ch->ssl, data, n, &got);
        if (ret != 1)
            return fc_tls_client_failure(ch->ssl, ret, "waiting for", err);
        data += got;
        n -= got;
    }
    return FC_OK;
}

bool fc_channel_input_waiting(const fc_channel *ch)
{
    if (ch->ssl && SSL_pending(ch->ssl) > 0)
        return true;
    struct pollfd pfd = {.fd = ch->fd, .events = POLLIN};
    return poll(&pfd, 1, 0) > 0;
}

void fc_channel_close(fc_channel *ch)
{
    SSL_free(ch->ssl);
    ch->ssl = NULL;
    if (ch->fd >= 0)
        close(ch->fd);
    ch->fd = -1;
}
