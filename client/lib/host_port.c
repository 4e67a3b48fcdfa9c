/* host_port.c — see host_port.h. */
#include "host_port.h"

#include <stdio.h>
#include <string.h>

#include "fc_error.h"
#include "wire.h"

static fc_code copy_host(const char *text, const char *begin, size_t len, char host[FC_HOST_MAX],
                         fc_error *err)
{
    if (len == 0)
        return fc_error_set(err, FC_ERR_USAGE, "server address \"%s\" has no host", text);
    if (len >= FC_HOST_MAX)
        return fc_error_set(err, FC_ERR_USAGE, "server address \"%s\" has a host longer than %d bytes",
                            text, FC_HOST_MAX - 1);
    memcpy(host, begin, len);
    host[len] = '\0';
    return FC_OK;
}

/* Digits only, no sign or spaces, so "7450x" or "+80" are refused rather than
 * silently read as something else. */
static fc_code copy_port(const char *text, const char *digits, char port[FC_PORT_MAX], fc_error *err)
{
    size_t len = strlen(digits);
    unsigned value = 0;
    if (len == 0 || len > 5)
        return fc_error_set(err, FC_ERR_USAGE, "server address \"%s\" needs a port in 1..65535", text);
    for (size_t i = 0; i < len; i++) {
        if (digits[i] < '0' || digits[i] > '9')
            return fc_error_set(err, FC_ERR_USAGE, "server address \"%s\" has a non-numeric port", text);
        value = value * 10 + (unsigned)(digits[i] - '0');
    }
    if (value < 1 || value > 65535)
        return fc_error_set(err, FC_ERR_USAGE, "server address \"%s\" needs a port in 1..65535", text);
    snprintf(port, FC_PORT_MAX, "%u", value);
    return FC_OK;
}

static fc_code use_default_port(char port[FC_PORT_MAX])
{
    snprintf(port, FC_PORT_MAX, "%u", (unsigned)FC_DEFAULT_PORT);
    return FC_OK;
}

static fc_code parse_bracketed(const char *text, char host[FC_HOST_MAX], char port[FC_PORT_MAX],
                               fc_error *err)
{
    const char *close = strchr(text, ']');
    if (!close)
        return fc_error_set(err, FC_ERR_USAGE, "server address \"%s\" lacks the closing ']'", text);
    fc_code code = copy_host(text, text + 1, (size_t)(close - text - 1), host, err);
    if (code != FC_OK)
        return code;
    if (close[1] == '\0')
        return use_default_port(port);
    if (close[1] != ':')
        return fc_error_set(err, FC_ERR_USAGE, "server address \"%s\" has text after ']' that is not \":PORT\"",
                            text);
    return copy_port(text, close + 2, port, err);
}

fc_code fc_host_port_parse(const char *text, char host[FC_HOST_MAX], char port[FC_PORT_MAX],
                           fc_error *err)
{
    if (!text)
        return fc_error_set(err, FC_ERR_USAGE, "no server address given");
    if (text[0] == '[')
        return parse_bracketed(text, host, port, err);

    const char *colon = strchr(text, ':');
    bool bare_ipv6 = colon && strchr(colon + 1, ':');
    if (!colon || bare_ipv6) {
        fc_code code = copy_host(text, text, strlen(text), host, err);
        return code != FC_OK ? code : use_default_port(port);
    }
    fc_code code = copy_host(text, text, (size_t)(colon - text), host, err);
    if (code != FC_OK)
        return code;
    return copy_port(text, colon + 1, port, err);
}
