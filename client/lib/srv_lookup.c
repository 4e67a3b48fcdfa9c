/* srv_lookup.c — see srv_lookup.h. The message is built, sent and parsed by
 * libresolv (res_nquery); srv_answer.c reads the answer. Each lookup has its own resolver state, so nothing is shared between
 * threads or clients. */
#include "srv_lookup.h"

#include <arpa/inet.h>
#include <arpa/nameser.h>
#include <netdb.h>
#include <netinet/in.h>
#include <resolv.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "srv_answer.h"

#define ANSWER_MAX 65536   /* the largest DNS message (over TCP, when the UDP answer was truncated) */

/* "ADDR" or "ADDR:PORT" (the HOST:PORT grammar, port 53 when none) into an
 * IPv4 socket address. */
static fc_code parse_dns_server(const char *text, struct sockaddr_in *out, fc_error *err)
{
    static const fc_host_port_rules rules = {FC_DNS_SERVER_ENV, 53, false};
    char host[FC_HOST_MAX];
    char port[FC_PORT_MAX];
    fc_code code = fc_host_port_parse(text, &rules, host, port, err);
    if (code != FC_OK)
        return code;
    memset(out, 0, sizeof *out);
    out->sin_family = AF_INET;
    out->sin_port = htons((uint16_t)atoi(port));
    if (inet_pton(AF_INET, host, &out->sin_addr) != 1)
        return fc_error_set(err, FC_ERR_USAGE, FC_DNS_SERVER_ENV "=\"%s\": \"%s\" is not an IPv4 address", text,
                            host);
    return FC_OK;
}

static fc_code open_resolver(res_state state, fc_error *err)
{
    memset(state, 0, sizeof *state);
    if (res_ninit(state) != 0)
        return fc_error_set(err, FC_ERR_CONNECT, "cannot initialise the DNS resolver (/etc/resolv.conf)");
    const char *server = getenv(FC_DNS_SERVER_ENV);
    if (!server || !*server)
        return FC_OK;
    struct sockaddr_in address;
    if (parse_dns_server(server, &address, err) != FC_OK) {
        res_nclose(state);
        return FC_ERR_USAGE;
    }
    state->nsaddr_list[0] = address;
    state->nscount = 1;
    return FC_OK;
}

static const char *query_failure(int h_error)
{
    switch (h_error) {
    case HOST_NOT_FOUND: return "no such name";
    case NO_DATA: return "the name has no SRV records";
    case TRY_AGAIN: return "no answer from the DNS server (timed out or refused)";
    default: return "the DNS server failed";
    }
}

fc_code fc_srv_lookup(const char *name, fc_srv_target *targets, size_t max, size_t *count, fc_error *err)
{
    *count = 0;
    struct __res_state state;
    fc_code code = open_resolver(&state, err);
    if (code != FC_OK)
        return code;
    unsigned char *answer = malloc(ANSWER_MAX);
    if (!answer) {
        res_nclose(&state);
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for a DNS answer");
    }
    int length = res_nquery(&state, name, ns_c_in, ns_t_srv, answer, ANSWER_MAX);
    if (length < 0)
        code = fc_error_set(err, FC_ERR_CONNECT, "SRV lookup of %s: %s", name, query_failure(state.res_h_errno));
    else
        code = fc_srv_parse_answer(answer, length, name, targets, max, count, err);
    free(answer);
    res_nclose(&state);
    return code;
}
