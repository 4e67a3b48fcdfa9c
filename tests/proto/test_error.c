/* test_error.c — error values: formatting, truncation, clearing and code names. */
#include <string.h>

#include "fc_error.h"
#include "test_util.h"

static void test_set_fills_code_and_message(void)
{
    fc_error err;
    CHECK_CODE(fc_error_set(&err, FC_ERR_LIMIT, "%d particles exceed %s", 17, "the limit"), FC_ERR_LIMIT);
    CHECK_CODE(err.code, FC_ERR_LIMIT);
    CHECK(strcmp(err.message, "17 particles exceed the limit") == 0);
}

static void test_set_without_error_returns_code(void)
{
    CHECK_CODE(fc_error_set(NULL, FC_ERR_IO, "ignored %s", "text"), FC_ERR_IO);
}

static void test_long_message_is_cut_and_terminated(void)
{
    char long_text[1000];
    memset(long_text, 'x', sizeof long_text - 1);
    long_text[sizeof long_text - 1] = '\0';
    fc_error err;
    fc_error_set(&err, FC_ERR_PARSE, "%s", long_text);
    CHECK(strlen(err.message) == FC_ERROR_MESSAGE_MAX - 1);
    CHECK(err.message[FC_ERROR_MESSAGE_MAX - 2] == 'x');
}

static void test_clear(void)
{
    fc_error err;
    fc_error_set(&err, FC_ERR_GL, "context lost");
    fc_error_clear(&err);
    CHECK_CODE(err.code, FC_OK);
    CHECK(err.message[0] == '\0');
    fc_error_clear(NULL);
}

static void test_code_names(void)
{
    CHECK(strcmp(fc_code_name(FC_OK), "ok") == 0);
    CHECK(strcmp(fc_code_name(FC_ERR_MALFORMED), "malformed") == 0);
    CHECK(strcmp(fc_code_name(FC_ERR_BAD_MAGIC), "bad_magic") == 0);
    CHECK(strcmp(fc_code_name(FC_ERR_INVALID_VALUE), "invalid_value") == 0);
    CHECK(strcmp(fc_code_name(FC_ERR_USAGE), "usage") == 0);
    CHECK(strcmp(fc_code_name((fc_code)55), "unknown") == 0);
    CHECK(strcmp(fc_code_name((fc_code)-1), "unknown") == 0);

    /* Every defined code has its own name. */
    const fc_code codes[] = {FC_ERR_BAD_MAGIC, FC_ERR_VERSION, FC_ERR_UNKNOWN_TYPE, FC_ERR_TOO_LARGE,
                             FC_ERR_MALFORMED, FC_ERR_BAD_STATE, FC_ERR_INVALID_VALUE, FC_ERR_LIMIT,
                             FC_ERR_RENDER, FC_ERR_ENCODE, FC_ERR_INTERNAL, FC_ERR_UNAUTHORIZED,
                             FC_ERR_DUPLICATE, FC_ERR_INCONSISTENT, FC_ERR_INCOMPLETE, FC_ERR_IO, FC_ERR_CONNECT, FC_ERR_CLOSED, FC_ERR_PROTOCOL,
                             FC_ERR_PARSE, FC_ERR_GL, FC_ERR_NOMEM, FC_ERR_USAGE, FC_ERR_TLS_REQUIRED,
                             FC_ERR_TLS_UNKNOWN_CA, FC_ERR_TLS_NAME_MISMATCH, FC_ERR_TLS_EXPIRED,
                             FC_ERR_TLS_PLAINTEXT_PEER, FC_ERR_TLS_CLIENT_CERT, FC_ERR_TLS};
    size_t n = sizeof codes / sizeof codes[0];
    for (size_t i = 0; i < n; i++) {
        CHECK_MSG(strcmp(fc_code_name(codes[i]), "unknown") != 0, "code %d has no name", (int)codes[i]);
        for (size_t j = i + 1; j < n; j++)
            CHECK_MSG(strcmp(fc_code_name(codes[i]), fc_code_name(codes[j])) != 0, "codes %d and %d share a name",
                      (int)codes[i], (int)codes[j]);
    }
}

int main(void)
{
    test_set_fills_code_and_message();
    test_set_without_error_returns_code();
    test_long_message_is_cut_and_terminated();
    test_clear();
    test_code_names();
    return test_result();
}
