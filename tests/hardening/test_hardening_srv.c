/* test_hardening_srv.c — hostile DNS answers for "srv:" addresses: a broken or
 * malicious DNS server's bytes, fed to the SRV answer reader the client uses
 * (libresolv parses). Each gets a typed error (FC_ERR_PROTOCOL, or
 * FC_ERR_CONNECT when nothing usable remains) and no read outside the message
 * (the sanitizer build checks that), and a good answer after them still reads. */
#include <stdbool.h>
#include <stdio.h>
#include <string.h>

#include "fc_error.h"
#include "srv_answer.h"
#include "test_util.h"

typedef struct message {
    unsigned char bytes[4096];
    int length;
} message;

static void put16(message *m, unsigned v)
{
    m->bytes[m->length++] = (unsigned char)(v >> 8);
    m->bytes[m->length++] = (unsigned char)v;
}

static void put_name(message *m, const char *dotted)
{
    while (*dotted) {
        const char *dot = strchr(dotted, '.');
        size_t len = dot ? (size_t)(dot - dotted) : strlen(dotted);
        m->bytes[m->length++] = (unsigned char)len;
        memcpy(m->bytes + m->length, dotted, len);
        m->length += (int)len;
        dotted += len + (dot ? 1 : 0);
    }
    m->bytes[m->length++] = 0;
}

/* A response header with `answers` records and the question _fc._tcp.t IN SRV. */
static void start(message *m, unsigned answers)
{
    memset(m, 0, sizeof *m);
    put16(m, 0x1234);
    put16(m, 0x8180);   /* response, recursion desired and available, no error */
    put16(m, 1);
    put16(m, answers);
    put16(m, 0);
    put16(m, 0);
    put_name(m, "_fc._tcp.t");
    put16(m, 33);       /* SRV */
    put16(m, 1);        /* IN */
}

/* An answer record for the question's name (pointer to offset 12) of the given
 * type and declared data length; the caller appends the data. */
static void record(message *m, unsigned type, unsigned rdlength)
{
    put16(m, 0xc00c);
    put16(m, type);
    put16(m, 1);
    put16(m, 0);
    put16(m, 60);
    put16(m, rdlength);
}

static void srv_record(message *m, unsigned priority, unsigned weight, unsigned port, const char *target)
{
    message name = {.length = 0};
    put_name(&name, target);
    record(m, 33, 6u + (unsigned)name.length);
    put16(m, priority);
    put16(m, weight);
    put16(m, port);
    memcpy(m->bytes + m->length, name.bytes, (size_t)name.length);
    m->length += name.length;
}

static fc_code parse(const message *m, fc_srv_target *targets, size_t *count, fc_error *err)
{
    return fc_srv_parse_answer(m->bytes, m->length, "_fc._tcp.t", targets, FC_SRV_MAX_TARGETS, count, err);
}

static void expect(const char *what, const message *m, fc_code expected)
{
    fc_srv_target targets[FC_SRV_MAX_TARGETS];
    size_t count = 99;
    fc_error err;
    fc_error_clear(&err);
    fc_code code = parse(m, targets, &count, &err);
    CHECK_MSG(code == expected && err.message[0] != '\0', "%s: code %d (%s), expected %d", what, code, err.message,
              expected);
    printf("%-44s -> %d: %s\n", what, code, err.message);
}

static void good_answer_reads(void)
{
    message m;
    start(&m, 2);
    srv_record(&m, 0, 10, 7450, "node-a.fc.test");
    record(&m, 5, 2);   /* a CNAME among them is skipped */
    put16(&m, 0xc00c);
    fc_srv_target targets[FC_SRV_MAX_TARGETS];
    size_t count = 0;
    fc_error err;
    CHECK(parse(&m, targets, &count, &err) == FC_OK && count == 1 && strcmp(targets[0].host, "node-a.fc.test") == 0 &&
          targets[0].port == 7450 && targets[0].weight == 10);
}

int main(void)
{
    message m;
    start(&m, 0);
    m.length = 7;
    expect("header cut short", &m, FC_ERR_PROTOCOL);

    start(&m, 3);
    srv_record(&m, 0, 10, 7450, "a.fc");
    expect("3 records announced, 1 present", &m, FC_ERR_PROTOCOL);

    start(&m, 1);
    record(&m, 33, 3);
    put16(&m, 1);
    m.bytes[m.length++] = 0;
    expect("SRV data of 3 bytes", &m, FC_ERR_PROTOCOL);

    start(&m, 1);
    record(&m, 33, 40);
    put16(&m, 0);
    expect("data length beyond the message", &m, FC_ERR_PROTOCOL);

    start(&m, 1);
    record(&m, 33, 8);
    put16(&m, 0);
    put16(&m, 0);
    put16(&m, 7450);
    put16(&m, 0xc000u | (unsigned)m.length);   /* the target points at itself */
    expect("target name pointing at itself", &m, FC_ERR_PROTOCOL);

    start(&m, 1);
    record(&m, 33, 8);
    put16(&m, 0);
    put16(&m, 0);
    put16(&m, 7450);
    put16(&m, 0xcfff);   /* pointer past the end */
    expect("target name pointer past the end", &m, FC_ERR_PROTOCOL);

    start(&m, 1);
    {
        message name = {.length = 0};
        for (int label = 0; label < 5; label++) {   /* 5 labels of 63 bytes: 320 > 255 */
            name.bytes[name.length++] = 63;
            memset(name.bytes + name.length, 'x', 63);
            name.length += 63;
        }
        name.bytes[name.length++] = 0;
        record(&m, 33, 6u + (unsigned)name.length);
        put16(&m, 0);
        put16(&m, 0);
        put16(&m, 7450);
        memcpy(m.bytes + m.length, name.bytes, (size_t)name.length);
        m.length += name.length;
    }
    expect("target name of 320 bytes", &m, FC_ERR_PROTOCOL);

    start(&m, 1);
    srv_record(&m, 0, 0, 0, "");
    expect("only the \".\" target", &m, FC_ERR_CONNECT);

    start(&m, 1);
    record(&m, 1, 4);   /* an A record, no SRV */
    put16(&m, 0x7f00);
    put16(&m, 1);
    expect("no SRV record in the answer", &m, FC_ERR_CONNECT);

    /* More records than a client keeps: the first FC_SRV_MAX_TARGETS, no overflow. */
    start(&m, 100);
    for (int i = 0; i < 100; i++) {
        char host[16];
        snprintf(host, sizeof host, "n%d.fc", i);
        srv_record(&m, 0, 1, (unsigned)(7000 + i), host);
    }
    fc_srv_target targets[FC_SRV_MAX_TARGETS];
    size_t count = 0;
    fc_error err;
    CHECK(parse(&m, targets, &count, &err) == FC_OK && count == FC_SRV_MAX_TARGETS &&
          targets[FC_SRV_MAX_TARGETS - 1].port == 7000 + FC_SRV_MAX_TARGETS - 1);

    good_answer_reads();
    return test_result();
}
