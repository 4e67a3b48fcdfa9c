/* test_host_port.c — the HOST:PORT grammar (fc_host_port.h): every form it
 * accepts with the host and port it yields, and every malformed address with
 * the exact error it gives, under the client's and the listener's rules. */
#include <string.h>

#include "fc_error.h"
#include "fc_host_port.h"
#include "test_util.h"

static const fc_host_port_rules listen_rules = {"--listen", FC_DEFAULT_PORT, true};
static const fc_host_port_rules port_required = {"--metrics-listen", 0, true};

typedef struct good_case {
    const fc_host_port_rules *rules;
    const char *text;
    const char *host;
    const char *port;
} good_case;

typedef struct bad_case {
    const fc_host_port_rules *rules;
    const char *text;
    const char *message;
} bad_case;

static const good_case good[] = {
    {&fc_server_address_rules, "render-node:7451", "render-node", "7451"},
    {&fc_server_address_rules, "10.0.0.2:80", "10.0.0.2", "80"},
    {&fc_server_address_rules, "render-node", "render-node", "7450"},
    {&fc_server_address_rules, "[::1]:9000", "::1", "9000"},
    {&fc_server_address_rules, "[::1]", "::1", "7450"},
    {&fc_server_address_rules, "[fe80::1%eth0]:1", "fe80::1%eth0", "1"},
    {&fc_server_address_rules, "host:007450", "host", "7450"},
    {&fc_server_address_rules, "host:65535", "host", "65535"},
    {&listen_rules, "0.0.0.0:0", "0.0.0.0", "0"},
    {&listen_rules, "[::]:0", "::", "0"},
    {&listen_rules, "0.0.0.0", "0.0.0.0", "7450"},
    {&port_required, "127.0.0.1:9090", "127.0.0.1", "9090"},
};

static const bad_case bad[] = {
    {&fc_server_address_rules, "::1", "server address \"::1\": an IPv6 address needs brackets: [ADDR] or [ADDR]:PORT"},
    {&fc_server_address_rules, "fe80::1:7450",
     "server address \"fe80::1:7450\": an IPv6 address needs brackets: [ADDR] or [ADDR]:PORT"},
    {&fc_server_address_rules, "", "server address: none given"},
    {&fc_server_address_rules, NULL, "server address: none given"},
    {&fc_server_address_rules, ":7450", "server address \":7450\": no host"},
    {&fc_server_address_rules, "[]:7450", "server address \"[]:7450\": no host"},
    {&fc_server_address_rules, "host:", "server address \"host:\": the port must be a number from 1 to 65535"},
    {&fc_server_address_rules, "host:0", "server address \"host:0\": the port must be a number from 1 to 65535"},
    {&fc_server_address_rules, "host:65536",
     "server address \"host:65536\": the port must be a number from 1 to 65535"},
    {&fc_server_address_rules, "host:99999999999999999999",
     "server address \"host:99999999999999999999\": the port must be a number from 1 to 65535"},
    {&fc_server_address_rules, "host:+80", "server address \"host:+80\": the port must be a number from 1 to 65535"},
    {&fc_server_address_rules, "host:http",
     "server address \"host:http\": the port must be a number from 1 to 65535"},
    {&fc_server_address_rules, "host:80 ", "server address \"host:80 \": the port must be a number from 1 to 65535"},
    {&fc_server_address_rules, "[::1", "server address \"[::1\": lacks the closing ']'"},
    {&fc_server_address_rules, "[::1]x", "server address \"[::1]x\": has text after ']' that is not \":PORT\""},
    {&listen_rules, "host:65536", "--listen \"host:65536\": the port must be a number from 0 to 65535"},
    {&listen_rules, "::", "--listen \"::\": an IPv6 address needs brackets: [ADDR] or [ADDR]:PORT"},
    {&port_required, "127.0.0.1", "--metrics-listen \"127.0.0.1\": needs a port (HOST:PORT or [IPV6]:PORT)"},
    {&port_required, "[::1]", "--metrics-listen \"[::1]\": needs a port (HOST:PORT or [IPV6]:PORT)"},
};

static void test_good_addresses(void)
{
    for (size_t i = 0; i < sizeof good / sizeof good[0]; i++) {
        char host[FC_HOST_MAX] = "", port[FC_PORT_MAX] = "";
        fc_error err;
        fc_code code = fc_host_port_parse(good[i].text, good[i].rules, host, port, &err);
        CHECK_MSG(code == FC_OK, "\"%s\": %s", good[i].text, err.message);
        CHECK_MSG(strcmp(host, good[i].host) == 0, "\"%s\": host \"%s\", expected \"%s\"", good[i].text, host,
                  good[i].host);
        CHECK_MSG(strcmp(port, good[i].port) == 0, "\"%s\": port \"%s\", expected \"%s\"", good[i].text, port,
                  good[i].port);
    }
}

static void test_bad_addresses(void)
{
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        char host[FC_HOST_MAX], port[FC_PORT_MAX];
        fc_error err;
        fc_error_clear(&err);
        CHECK_CODE(fc_host_port_parse(bad[i].text, bad[i].rules, host, port, &err), FC_ERR_USAGE);
        CHECK_MSG(strcmp(err.message, bad[i].message) == 0, "\"%s\": message \"%s\", expected \"%s\"",
                  bad[i].text ? bad[i].text : "(null)", err.message, bad[i].message);
    }
}

/* The longest host fits; one byte more is refused without overrunning host[]. */
static void test_host_length(void)
{
    char text[FC_HOST_MAX + 8];
    memset(text, 'h', FC_HOST_MAX - 1);
    strcpy(text + FC_HOST_MAX - 1, ":1");
    char host[FC_HOST_MAX], port[FC_PORT_MAX];
    fc_error err;
    CHECK_CODE(fc_host_port_parse(text, &fc_server_address_rules, host, port, &err), FC_OK);
    CHECK(strlen(host) == FC_HOST_MAX - 1);
    memset(text, 'h', FC_HOST_MAX);
    strcpy(text + FC_HOST_MAX, ":1");
    CHECK_CODE(fc_host_port_parse(text, &fc_server_address_rules, host, port, &err), FC_ERR_USAGE);
    CHECK_MSG(strstr(err.message, "the host is longer than 255 bytes") != NULL, "%s", err.message);
}

static void test_default_server(void)
{
    CHECK(strcmp(FC_DEFAULT_SERVER, "127.0.0.1:7450") == 0);
    char host[FC_HOST_MAX], port[FC_PORT_MAX];
    fc_error err;
    CHECK_CODE(fc_host_port_parse(FC_DEFAULT_SERVER, &fc_server_address_rules, host, port, &err), FC_OK);
    CHECK(strcmp(host, FC_DEFAULT_HOST) == 0);
}

int main(void)
{
    test_good_addresses();
    test_bad_addresses();
    test_host_length();
    test_default_server();
    return test_result();
}
