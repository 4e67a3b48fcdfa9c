/* test_token_file.c — the --token-file format both fluidcastd and the CLI
 * read (fc_token_file_read): the token on one line, one LF or CRLF allowed
 * after it; each file content with the token or the exact error it gives. */
#define _POSIX_C_SOURCE 200809L   /* mkdtemp */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fc_error.h"
#include "fc_token_file.h"
#include "test_util.h"

typedef struct token_case {
    const char *content;
    size_t size;
    fc_code code;
    const char *token_or_problem;   /* the token, or the message after "--token-file PATH: " */
} token_case;

#define TEXT(s) s, sizeof s - 1

static const token_case cases[] = {
    {TEXT("hunter2"), FC_OK, "hunter2"},
    {TEXT("hunter2\n"), FC_OK, "hunter2"},
    {TEXT("hunter2\r\n"), FC_OK, "hunter2"},
    {TEXT(" spaced out "), FC_OK, " spaced out "},
    {TEXT(""), FC_ERR_USAGE, "the file holds no token"},
    {TEXT("\n"), FC_ERR_USAGE, "the file holds no token"},
    {TEXT("hunter2\n\n"), FC_ERR_USAGE, "the file holds more than one line"},
    {TEXT("hunter2\n# a comment\n"), FC_ERR_USAGE, "the file holds more than one line"},
    {TEXT("a\0b"), FC_ERR_USAGE, "the token contains a NUL byte"},
};

static char dir[] = "/tmp/fc_token_XXXXXX";

static void write_file(const char *path, const char *bytes, size_t size)
{
    FILE *f = fopen(path, "wb");
    CHECK_MSG(f && fwrite(bytes, 1, size, f) == size, "cannot write %s", path);
    if (f)
        fclose(f);
}

static void test_cases(const char *path)
{
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        write_file(path, cases[i].content, cases[i].size);
        char token[FC_HELLO_TOKEN_MAX + 1] = "";
        fc_error err;
        fc_error_clear(&err);
        fc_code code = fc_token_file_read(path, token, &err);
        CHECK_MSG(code == cases[i].code, "case %zu: code %d (%s)", i, (int)code, err.message);
        char expected[512];
        if (cases[i].code == FC_OK) {
            CHECK_MSG(strcmp(token, cases[i].token_or_problem) == 0, "case %zu: token \"%s\"", i, token);
            continue;
        }
        snprintf(expected, sizeof expected, "--token-file %s: %s", path, cases[i].token_or_problem);
        CHECK_MSG(strcmp(err.message, expected) == 0, "case %zu: \"%s\"", i, err.message);
    }
}

/* The longest token with a CRLF is read; one byte more is refused. */
static void test_length(const char *path)
{
    char text[FC_HELLO_TOKEN_MAX + 3];
    memset(text, 'k', sizeof text);
    memcpy(text + FC_HELLO_TOKEN_MAX, "\r\n", 2);
    write_file(path, text, FC_HELLO_TOKEN_MAX + 2);
    char token[FC_HELLO_TOKEN_MAX + 1];
    fc_error err;
    CHECK_CODE(fc_token_file_read(path, token, &err), FC_OK);
    CHECK(strlen(token) == FC_HELLO_TOKEN_MAX);
    memset(text, 'k', sizeof text);
    write_file(path, text, FC_HELLO_TOKEN_MAX + 1);
    CHECK_CODE(fc_token_file_read(path, token, &err), FC_ERR_USAGE);
    char expected[512];
    snprintf(expected, sizeof expected, "--token-file %s: the token is longer than %d bytes", path,
             FC_HELLO_TOKEN_MAX);
    CHECK_MSG(strcmp(err.message, expected) == 0, "%s", err.message);
    write_file(path, text, FC_HELLO_TOKEN_MAX + 3);
    CHECK_CODE(fc_token_file_read(path, token, &err), FC_ERR_USAGE);
    CHECK_MSG(strcmp(err.message, expected) == 0, "%s", err.message);
}

static void test_missing(const char *path)
{
    unlink(path);
    char token[FC_HELLO_TOKEN_MAX + 1];
    fc_error err;
    CHECK_CODE(fc_token_file_read(path, token, &err), FC_ERR_IO);
    char expected[512];
    snprintf(expected, sizeof expected, "--token-file %s: cannot open: No such file or directory", path);
    CHECK_MSG(strcmp(err.message, expected) == 0, "%s", err.message);
}

int main(void)
{
    if (!mkdtemp(dir)) {
        CHECK_MSG(0, "cannot make a temporary folder");
        return test_result();
    }
    char path[128];
    snprintf(path, sizeof path, "%s/token", dir);
    test_cases(path);
    test_length(path);
    test_missing(path);
    rmdir(dir);
    return test_result();
}
