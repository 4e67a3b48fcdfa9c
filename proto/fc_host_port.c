/* fc_host_port.c — see fc_host_port.h. */
#include "fc_host_port.h"

#include <stdio.h>
#include <string.h>

#include "fc_error.h"

const fc_host_port_rules fc_server_address_rules = {"server address", FC_DEFAULT_PORT, false};

static fc_code refuse(const fc_host_port_rules *rules, const char *text, const char *problem, fc_error *err)
{
    return fc_error_set(err, FC_ERR_USAGE, "%s \"%s\": %s", rules->what, text, problem);
}

static fc_code copy_host(const fc_host_port_rules *rules, const char *text, const char *begin, size_t len,
                         char host[FC_HOST_MAX], fc_error *err)
{
    if (len == 0)
        return refuse(rules, text, "no host", err);
    if (len >= FC_HOST_MAX)
        return fc_error_set(err, FC_ERR_USAGE, "%s \"%.40s...\": the host is longer than %d bytes", rules->what,
                            text, FC_HOST_MAX - 1);
    memcpy(host, begin, len);
    host[len] = '\0';
    return FC_OK;
}

/* Digits only, no sign or spaces, so "7450x" or "+80" are refused rather than
 * silently read as something else. */
static fc_code copy_port(const fc_host_port_rules *rules, const char *text, const char *digits,
                         char port[FC_PORT_MAX], fc_error *err)
{
    const char *range = rules->port_zero ? "the port must be a number from 0 to 65535"
                                         : "the port must be a number from 1 to 65535";
    size_t len = strlen(digits);
    if (len == 0)
        return refuse(rules, text, range, err);
    unsigned long value = 0;
    for (size_t i = 0; i < len; i++) {
        if (digits[i] < '0' || digits[i] > '9' || value > 65535)
            return refuse(rules, text, range, err);
        value = value * 10 + (unsigned long)(digits[i] - '0');
    }
    if (value > 65535 || (value == 0 && !rules->port_zero))
        return refuse(rules, text, range, err);
    snprintf(port, FC_PORT_MAX, "%lu", value);
    return FC_OK;
}

static fc_code use_default_port(const fc_host_port_rules *rules, const char *text, char port[FC_PORT_MAX],
                                fc_error *err)
{
    if (rules->default_port == 0)
        return refuse(rules, text, "needs a port (HOST:PORT or [IPV6]:PORT)", err);
    snprintf(port, FC_PORT_MAX, "%u", (unsigned)rules->default_port);
    return FC_OK;
}

static fc_code parse_bracketed(const fc_host_port_rules *rules, const char *text, char host[FC_HOST_MAX],
                               char port[FC_PORT_MAX], fc_error *err)
{
    const char *close = strchr(text, ']');
    if (!close)
        return refuse(rules, text, "lacks the closing ']'", err);
    fc_code code = copy_host(rules, text, text + 1, (size_t)(close - text - 1), host, err);
    if (code != FC_OK)
        return code;
    if (close[1] == '\0')
        return use_default_port(rules, text, port, err);
    if (close[1] != ':')
        return refuse(rules, text, "has text after ']' that is not \":PORT\"", err);
    return copy_port(rules, text, close + 2, port, err);
}

fc_code fc_host_port_parse(const char *text, const fc_host_port_rules *rules, char host[FC_HOST_MAX],
                           char port[FC_PORT_MAX], fc_error *err)
{
    if (!text || text[0] == '\0')
        return fc_error_set(err, FC_ERR_USAGE, "%s: none given", rules->what);
    if (text[0] == '[')
        return parse_bracketed(rules, text, host, port, err);
    const char *colon = strchr(text, ':');
    if (colon && strchr(colon + 1, ':'))
        return refuse(rules, text, "an IPv6 address needs brackets: [ADDR] or [ADDR]:PORT", err);
    fc_code code = copy_host(rules, text, text, colon ? (size_t)(colon - text) : strlen(text), host, err);
    if (code != FC_OK)
        return code;
    return colon ? copy_port(rules, text, colon + 1, port, err) : use_default_port(rules, text, port, err);
}
