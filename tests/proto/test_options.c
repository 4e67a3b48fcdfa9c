/* test_options.c — the shared option parser (fc_options.h): "--name value",
 * "--name=value", flags, positional arguments, -h/--help, the usage errors'
 * exact texts, defaults applied from the table, and the generated help. */
#define _POSIX_C_SOURCE 200809L   /* open_memstream */
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "fc_options.h"
#include "test_util.h"

typedef struct sample {
    char name[32];
    long count;
    int verbose;
    char positional[64];
} sample;

static fc_code set_name(void *o, const char *option, const char *value, fc_error *err)
{
    (void)option, (void)err;
    snprintf(((sample *)o)->name, sizeof ((sample *)o)->name, "%s", value);
    return FC_OK;
}

static fc_code set_count(void *o, const char *option, const char *value, fc_error *err)
{
    char *end = NULL;
    long n = strtol(value, &end, 10);
    if (end == value || *end != '\0')
        return fc_error_set(err, FC_ERR_USAGE, "%s '%s': not a number", option, value);
    ((sample *)o)->count = n;
    return FC_OK;
}

static fc_code set_verbose(void *o, const char *option, const char *value, fc_error *err)
{
    (void)option, (void)err;
    ((sample *)o)->verbose = value == NULL;   /* flags get no value */
    return FC_OK;
}

static fc_code add_positional(void *o, const char *arg, fc_error *err)
{
    (void)err;
    strncat(((sample *)o)->positional, arg, sizeof ((sample *)o)->positional - 1 - strlen(((sample *)o)->positional));
    return FC_OK;
}

static const fc_option rows[] = {
    {"--name", "NAME", set_name, "what to call it", "anon"},
    {"--count", "N", set_count, "how many of them there are, a whole number that may be negative", "3"},
    {"--verbose", NULL, set_verbose, "say more", NULL},
    {"--hidden", "H", set_name, NULL, NULL},
};
static const fc_option_table with_args = {"prog sub", rows, sizeof rows / sizeof rows[0], add_positional, NULL};
static const fc_option_table plain = {"prog", rows, sizeof rows / sizeof rows[0], NULL, NULL};

typedef struct parse_case {
    const fc_option_table *table;
    const char *args[6];         /* NULL-terminated */
    fc_code code;
    const char *message;         /* for a failure */
    sample expected;             /* for success (defaults applied first) */
    bool help;
} parse_case;

#define NONE {.count = 0}   /* a failure leaves nothing to compare */

static const parse_case cases[] = {
    {&plain, {NULL}, FC_OK, NULL, {"anon", 3, 0, ""}, false},
    {&plain, {"--name", "x", "--count=7", NULL}, FC_OK, NULL, {"x", 7, 0, ""}, false},
    {&plain, {"--name=a=b", "--verbose", NULL}, FC_OK, NULL, {"a=b", 3, 1, ""}, false},
    {&plain, {"--name=", NULL}, FC_OK, NULL, {"", 3, 0, ""}, false},
    {&plain, {"--name", "-", NULL}, FC_OK, NULL, {"-", 3, 0, ""}, false},
    {&plain, {"--hidden", "h", NULL}, FC_OK, NULL, {"h", 3, 0, ""}, false},
    {&with_args, {"a", "--count", "-2", "b", "-", NULL}, FC_OK, NULL, {"anon", -2, 0, "ab-"}, false},
    {&plain, {"--count", "1", "-h", "--bogus", NULL}, FC_OK, NULL, {"anon", 1, 0, ""}, true},
    {&plain, {"--help", NULL}, FC_OK, NULL, {"anon", 3, 0, ""}, true},
    {&plain, {"--bogus", NULL}, FC_ERR_USAGE, "unknown option --bogus (see prog --help)", NONE, false},
    {&with_args, {"--bogus=1", NULL}, FC_ERR_USAGE, "unknown option --bogus=1 (see prog sub --help)", NONE, false},
    {&plain, {"--nam", "x", NULL}, FC_ERR_USAGE, "unknown option --nam (see prog --help)", NONE, false},
    {&plain, {"--names", "x", NULL}, FC_ERR_USAGE, "unknown option --names (see prog --help)", NONE, false},
    {&plain, {"--name", NULL}, FC_ERR_USAGE, "--name needs a value", NONE, false},
    {&plain, {"--verbose=yes", NULL}, FC_ERR_USAGE, "--verbose takes no value", NONE, false},
    {&plain, {"file", NULL}, FC_ERR_USAGE, "unexpected argument \"file\" (see prog --help)", NONE, false},
    {&plain, {"--count", "x", NULL}, FC_ERR_USAGE, "--count 'x': not a number", NONE, false},
    {&plain, {"--help=1", NULL}, FC_ERR_USAGE, "unknown option --help=1 (see prog --help)", NONE, false},
};

static int count_args(const char *const *args)
{
    int n = 0;
    while (args[n])
        n++;
    return n;
}

static void test_parse_cases(void)
{
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        const parse_case *c = &cases[i];
        sample got = {.count = 0};
        fc_error err;
        fc_error_clear(&err);
        CHECK_CODE(fc_options_set_defaults(c->table, &got, &err), FC_OK);
        bool help = !c->help;
        fc_code code = fc_options_parse(c->table, count_args(c->args), (char **)c->args, &got, &help, &err);
        CHECK_MSG(code == c->code, "case %zu: code %d, expected %d (%s)", i, (int)code, (int)c->code, err.message);
        if (c->code != FC_OK) {
            CHECK_MSG(strcmp(err.message, c->message) == 0, "case %zu: \"%s\", expected \"%s\"", i, err.message,
                      c->message);
            continue;
        }
        CHECK_MSG(help == c->help, "case %zu: help %d", i, (int)help);
        CHECK_MSG(strcmp(got.name, c->expected.name) == 0, "case %zu: name \"%s\"", i, got.name);
        CHECK_MSG(got.count == c->expected.count, "case %zu: count %ld", i, got.count);
        CHECK_MSG(got.verbose == c->expected.verbose, "case %zu: verbose %d", i, got.verbose);
        CHECK_MSG(strcmp(got.positional, c->expected.positional) == 0, "case %zu: positional \"%s\"", i,
                  got.positional);
    }
}

/* fc_options_take leaves what another table should take. */
static void test_take(void)
{
    char *args[] = {"--other", "--count", "5"};
    sample got = {.count = 0};
    fc_error err;
    bool known = true;
    int i = 0;
    CHECK_CODE(fc_options_take(&plain, 3, args, &i, &got, &known, &err), FC_OK);
    CHECK(!known && i == 0);
    i = 1;
    CHECK_CODE(fc_options_take(&plain, 3, args, &i, &got, &known, &err), FC_OK);
    CHECK(known && i == 2 && got.count == 5);
}

static void test_help_text(void)
{
    char *text = NULL;
    size_t size = 0;
    FILE *out = open_memstream(&text, &size);
    fc_options_print_help(out, &plain);
    fclose(out);
    const char *expected =
        "  --name NAME             what to call it (default anon)\n"
        "  --count N               how many of them there are, a whole number that may be\n"
        "                          negative (default 3)\n"
        "  --verbose               say more\n"
        "  -h, --help              show this help\n";
    CHECK_MSG(strcmp(text, expected) == 0, "help:\n%s", text);
    free(text);
}

int main(void)
{
    test_parse_cases();
    test_take();
    test_help_text();
    return test_result();
}
