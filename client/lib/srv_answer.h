/* srv_answer.h — the SRV records of a DNS answer, read from bytes that came
 * off the network (a hostile or broken DNS server is possible). */
#ifndef FC_SRV_ANSWER_H
#define FC_SRV_ANSWER_H

#include "srv_target.h"

/* Reads the SRV records (class IN) of the answer section of the DNS message
 * answer[0..length) into targets, at most `max`; *count says how many. `name`
 * is only for the messages. FC_ERR_PROTOCOL when the message, a record or a
 * target name does not parse or an SRV record is shorter than its fixed 7
 * bytes; FC_ERR_CONNECT when no usable record remains (none, or only the "."
 * target, which RFC 2782 uses to say the service is not offered). */
fc_code fc_srv_parse_answer(const unsigned char *answer, int length, const char *name, fc_srv_target *targets,
                            size_t max, size_t *count, fc_error *err);

#endif
