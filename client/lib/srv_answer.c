/* srv_answer.c — see srv_answer.h. The message is parsed by libresolv
 * (ns_initparse, ns_parserr, ns_get16, dn_expand), which bounds every read by
 * the message's end: no DNS parsing by hand. */
#include "srv_answer.h"

#include <arpa/nameser.h>
#include <netinet/in.h>
#include <resolv.h>
#include <stdbool.h>
#include <string.h>

#include "fc_error.h"

/* One SRV record's data: priority, weight, port (16 bits each), then the target
 * name, compressed against the whole message. */
static fc_code read_srv(const ns_msg *msg, const ns_rr *rr, fc_srv_target *out, fc_error *err)
{
    const unsigned char *data = ns_rr_rdata(*rr);
    if (ns_rr_rdlen(*rr) < 7)
        return fc_error_set(err, FC_ERR_PROTOCOL, "an SRV record of %u bytes is too short",
                            (unsigned)ns_rr_rdlen(*rr));
    out->priority = (uint16_t)ns_get16(data);
    out->weight = (uint16_t)ns_get16(data + 2);
    out->port = (uint16_t)ns_get16(data + 4);
    if (dn_expand(ns_msg_base(*msg), ns_msg_end(*msg), data + 6, out->host, (int)sizeof out->host) < 0)
        return fc_error_set(err, FC_ERR_PROTOCOL, "an SRV record's target name does not decode");
    return FC_OK;
}

/* Other record types in the answer section (a CNAME on the way) are skipped. */
fc_code fc_srv_parse_answer(const unsigned char *answer, int length, const char *name, fc_srv_target *targets,
                            size_t max, size_t *count, fc_error *err)
{
    ns_msg msg;
    if (ns_initparse(answer, length, &msg) < 0)
        return fc_error_set(err, FC_ERR_PROTOCOL, "the DNS answer for %s does not parse", name);
    *count = 0;
    bool dot_only = false;
    int records = ns_msg_count(msg, ns_s_an);
    for (int i = 0; i < records && *count < max; i++) {
        ns_rr rr;
        if (ns_parserr(&msg, ns_s_an, i, &rr) < 0)
            return fc_error_set(err, FC_ERR_PROTOCOL, "record %d of the DNS answer for %s does not parse", i, name);
        if (ns_rr_type(rr) != ns_t_srv || ns_rr_class(rr) != ns_c_in)
            continue;
        fc_srv_target target;
        fc_code code = read_srv(&msg, &rr, &target, err);
        if (code != FC_OK)
            return code;
        /* RFC 2782: a target of "." means the service is decidedly not available there. */
        if (target.host[0] == '\0' || strcmp(target.host, ".") == 0) {
            dot_only = true;
            continue;
        }
        targets[(*count)++] = target;
    }
    if (*count == 0)
        return fc_error_set(err, FC_ERR_CONNECT, "%s: %s", name,
                            dot_only ? "the SRV record says the service is not offered (target \".\")"
                                     : "the answer holds no SRV record");
    return FC_OK;
}
