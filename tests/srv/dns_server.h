/* dns_server.h — a real DNS server for the tests: dnsmasq on a random loopback
 * port, as a child of the test, answering SRV records from a generated
 * configuration and nothing else (no upstream, no /etc/hosts). */
#ifndef FC_TEST_DNS_SERVER_H
#define FC_TEST_DNS_SERVER_H

#include <stdbool.h>
#include <stdint.h>
#include <sys/types.h>

typedef struct fc_test_dns {
    pid_t pid;
    uint16_t port;
    char dir[64];        /* its configuration and log */
} fc_test_dns;

/* The dnsmasq binary, or NULL when it is not installed. */
const char *fc_test_dns_binary(void);

/* Starts dnsmasq serving `records`, lines of dnsmasq configuration such as
 * "srv-host=_fluidcast._tcp.fc.test,localhost,7450,0,10" (NULL-terminated),
 * on 127.0.0.1 at a random port in 20000-60000 (another one when that is
 * taken). `ready_name` is an SRV name among them: the start waits until it is
 * answered. false (with the reason printed) when it cannot start. */
bool fc_test_dns_start(fc_test_dns *dns, const char *const *records, const char *ready_name);

/* "127.0.0.1:PORT", for FLUIDCAST_DNS_SERVER. */
void fc_test_dns_address(const fc_test_dns *dns, char *out, size_t size);

/* SIGTERM to its process id, then waits for it. true when it exited cleanly. */
bool fc_test_dns_stop(fc_test_dns *dns);

#endif
