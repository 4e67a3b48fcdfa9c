/* test_auth_token.c — the token in HELLO, byte for byte as PROTOCOL.md 7.1
 * lays it out; the daemon's token comparison and token file loading. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "auth_token.h"
#include "fc_error.h"
#include "test_util.h"
#include "wire.h"

/* HELLO's payload: version 1..1, capabilities 0, name "ab", then the token "s3". */
static void test_hello_carries_token(void)
{
    static const uint8_t expected[] = {1, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 2, 0, 'a', 'b', 2, 0, 's', '3'};
    fc_hello in = {.version_min = 1, .version_max = 1, .client_name = "ab", .token = "s3"};
    fc_buf b;
    fc_buf_init(&b);
    fc_error err;
    CHECK_CODE(fc_wire_write_hello(&b, 7, &in, &err), FC_OK);
    CHECK(b.len == FC_WIRE_HEADER_SIZE + sizeof expected);
    CHECK(b.len >= FC_WIRE_HEADER_SIZE + sizeof expected &&
          memcmp(b.data + FC_WIRE_HEADER_SIZE, expected, sizeof expected) == 0);
    fc_hello out;
    CHECK_CODE(fc_wire_read_hello(expected, sizeof expected, &out, &err), FC_OK);
    CHECK(strcmp(out.token, "s3") == 0 && strcmp(out.client_name, "ab") == 0);
    /* Without a token the HELLO is the version-1 HELLO of old, and reads back with none. */
    fc_buf_reset(&b);
    in.token[0] = '\0';
    CHECK_CODE(fc_wire_write_hello(&b, 7, &in, &err), FC_OK);
    CHECK(b.len == FC_WIRE_HEADER_SIZE + sizeof expected - 4);
    CHECK_CODE(fc_wire_read_hello(expected, sizeof expected - 4, &out, &err), FC_OK);
    CHECK(out.token[0] == '\0');
    fc_buf_free(&b);
}

static void test_hello_token_bounds(void)
{
    enum { FIXED = 16 };
    uint8_t p[FIXED + 2 + FC_HELLO_TOKEN_MAX + 1];
    memset(p, 'x', sizeof p);
    const uint8_t fixed[FIXED] = {1, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 2, 0, 'a', 'b'};
    memcpy(p, fixed, FIXED);
    fc_hello out;
    fc_error err;
    /* Exactly the longest token is kept whole. */
    p[FIXED] = FC_HELLO_TOKEN_MAX & 0xff;
    p[FIXED + 1] = FC_HELLO_TOKEN_MAX >> 8;
    CHECK_CODE(fc_wire_read_hello(p, sizeof p - 1, &out, &err), FC_OK);
    CHECK(strlen(out.token) == FC_HELLO_TOKEN_MAX);
    /* One byte more is not cut to a prefix that might match: it counts as no token. */
    p[FIXED] = (FC_HELLO_TOKEN_MAX + 1) & 0xff;
    p[FIXED + 1] = (FC_HELLO_TOKEN_MAX + 1) >> 8;
    CHECK_CODE(fc_wire_read_hello(p, sizeof p, &out, &err), FC_OK);
    CHECK(out.token[0] == '\0');
    /* Bytes after client_name that are no complete token stay ignorable, as for any later field. */
    CHECK_CODE(fc_wire_read_hello(p, FIXED + 5, &out, &err), FC_OK);
    CHECK(out.token[0] == '\0' && strcmp(out.client_name, "ab") == 0);
    CHECK_CODE(fc_wire_read_hello(p, FIXED + 1, &out, &err), FC_OK);
    CHECK(out.token[0] == '\0');
    const uint8_t with_nul[] = {1, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 2, 0, 'a', 'b', 3, 0, 'k', 0, 'k'};
    CHECK_CODE(fc_wire_read_hello(with_nul, sizeof with_nul, &out, &err), FC_OK);
    CHECK(out.token[0] == '\0');
}

static void test_matches(void)
{
    CHECK(fc_auth_token_matches("secret", "secret"));
    CHECK(!fc_auth_token_matches("secret", "secreT"));
    CHECK(!fc_auth_token_matches("secret", "secre"));      /* a prefix */
    CHECK(!fc_auth_token_matches("secret", "secrets"));    /* an extension */
    CHECK(!fc_auth_token_matches("secret", ""));
    CHECK(!fc_auth_token_matches("a", "b"));
}

static void write_file(const char *path, const char *text, size_t len)
{
    FILE *f = fopen(path, "wb");
    CHECK(f && fwrite(text, 1, len, f) == len);
    if (f)
        fclose(f);
}

static void test_load(void)
{
    char dir[] = "/tmp/fc_auth_XXXXXX";
    CHECK(mkdtemp(dir) != NULL);
    char path[64];
    snprintf(path, sizeof path, "%s/token", dir);
    fc_auth_token t;
    fc_error err;

    write_file(path, "hunter2\r\n", 9);
    CHECK_CODE(fc_auth_token_load(path, "ignored", &t, &err), FC_OK);
    CHECK(strcmp(t.text, "hunter2") == 0 && fc_auth_token_required(&t));
    write_file(path, "\n", 1);
    CHECK_CODE(fc_auth_token_load(path, NULL, &t, &err), FC_ERR_USAGE);
    write_file(path, "a\0b", 3);
    CHECK_CODE(fc_auth_token_load(path, NULL, &t, &err), FC_ERR_USAGE);
    char longest[FC_HELLO_TOKEN_MAX + 1];
    memset(longest, 'k', sizeof longest);
    longest[FC_HELLO_TOKEN_MAX] = '\n';
    write_file(path, longest, FC_HELLO_TOKEN_MAX + 1);
    CHECK_CODE(fc_auth_token_load(path, NULL, &t, &err), FC_OK);
    CHECK(strlen(t.text) == FC_HELLO_TOKEN_MAX);
    memset(longest, 'k', sizeof longest);   /* one byte beyond the limit, no line end */
    write_file(path, longest, sizeof longest);
    CHECK_CODE(fc_auth_token_load(path, NULL, &t, &err), FC_ERR_USAGE);
    unlink(path);
    CHECK_CODE(fc_auth_token_load(path, NULL, &t, &err), FC_ERR_IO);
    rmdir(dir);

    CHECK_CODE(fc_auth_token_load(NULL, "from-env", &t, &err), FC_OK);
    CHECK(strcmp(t.text, "from-env") == 0);
    CHECK_CODE(fc_auth_token_load(NULL, "", &t, &err), FC_OK);
    CHECK(!fc_auth_token_required(&t));
    CHECK_CODE(fc_auth_token_load(NULL, NULL, &t, &err), FC_OK);
    CHECK(!fc_auth_token_required(&t));
}

int main(void)
{
    test_hello_carries_token();
    test_hello_token_bounds();
    test_matches();
    test_load();
    return test_result();
}
