/* fc_options.c — see fc_options.h. */
#include "fc_options.h"

#include <string.h>

#include "fc_error.h"

enum { HELP_COLUMN = 26, HELP_WIDTH = 80 };

bool fc_option_matches(const char *arg, const char *name)
{
    size_t len = strlen(name);
    return strncmp(arg, name, len) == 0 && (arg[len] == '\0' || arg[len] == '=');
}

const fc_option *fc_options_find(const fc_option_table *table, const char *arg, const char **inline_value)
{
    *inline_value = NULL;
    for (size_t i = 0; i < table->count; i++) {
        const fc_option *option = &table->options[i];
        if (fc_option_matches(arg, option->name)) {
            size_t len = strlen(option->name);
            if (arg[len] == '=')
                *inline_value = arg + len + 1;
            return option;
        }
    }
    return NULL;
}

static fc_code take_positional(const fc_option_table *table, const char *arg, void *target, fc_error *err)
{
    if (!table->positional)
        return fc_error_set(err, FC_ERR_USAGE, "unexpected argument \"%s\" (see %s --help)", arg, table->program);
    return table->positional(target, arg, err);
}

fc_code fc_options_take(const fc_option_table *table, int argc, char **argv, int *i, void *target, bool *known,
                        fc_error *err)
{
    const char *value;
    const fc_option *option = fc_options_find(table, argv[*i], &value);
    *known = option != NULL;
    if (!option)
        return FC_OK;
    if (!option->value_name && value)
        return fc_error_set(err, FC_ERR_USAGE, "%s takes no value", option->name);
    if (option->value_name && !value) {
        if (*i + 1 >= argc)
            return fc_error_set(err, FC_ERR_USAGE, "%s needs a value", option->name);
        value = argv[++*i];
    }
    return option->set(target, option->name, value, err);
}

static fc_code take_option(const fc_option_table *table, int argc, char **argv, int *i, void *target,
                           fc_error *err)
{
    bool known;
    fc_code code = fc_options_take(table, argc, argv, i, target, &known, err);
    if (!known && table->more)
        code = table->more(target, argc, argv, i, &known, err);
    if (!known)
        return fc_error_set(err, FC_ERR_USAGE, "unknown option %s (see %s --help)", argv[*i], table->program);
    return code;
}

fc_code fc_options_parse(const fc_option_table *table, int argc, char **argv, void *target, bool *help,
                         fc_error *err)
{
    *help = false;
    for (int i = 0; i < argc; i++) {
        const char *arg = argv[i];
        if (strcmp(arg, "--help") == 0 || strcmp(arg, "-h") == 0) {
            *help = true;
            return FC_OK;
        }
        bool positional = arg[0] != '-' || arg[1] == '\0';
        fc_code code = positional ? take_positional(table, arg, target, err)
                                  : take_option(table, argc, argv, &i, target, err);
        if (code != FC_OK)
            return code;
    }
    return FC_OK;
}

fc_code fc_options_set_defaults(const fc_option_table *table, void *target, fc_error *err)
{
    for (size_t i = 0; i < table->count; i++) {
        const fc_option *option = &table->options[i];
        if (!option->default_value)
            continue;
        fc_code code = option->set(target, option->name, option->default_value, err);
        if (code != FC_OK)
            return code;
    }
    return FC_OK;
}

/* Prints `len` bytes of a word at *column, first breaking the line when it
 * would pass HELP_WIDTH. */
static void print_word(FILE *out, const char *word, size_t len, int *column)
{
    if (*column > HELP_COLUMN && *column + 1 + (int)len > HELP_WIDTH) {
        fprintf(out, "\n%*s", HELP_COLUMN, "");
        *column = HELP_COLUMN;
    }
    if (*column > HELP_COLUMN) {
        fputc(' ', out);
        (*column)++;
    }
    fprintf(out, "%.*s", (int)len, word);
    *column += (int)len;
}

static void print_words(FILE *out, const char *text, int *column)
{
    while (*text) {
        text += strspn(text, " ");
        size_t len = strcspn(text, " ");
        if (len > 0)
            print_word(out, text, len, column);
        text += len;
    }
}

void fc_options_print_option(FILE *out, const fc_option *option)
{
    int column = fprintf(out, "  %s%s%s", option->name, option->value_name ? " " : "",
                         option->value_name ? option->value_name : "");
    if (column + 2 > HELP_COLUMN) {
        fputc('\n', out);
        column = 0;
    }
    fprintf(out, "%*s", HELP_COLUMN - column, "");
    column = HELP_COLUMN;
    print_words(out, option->help, &column);
    if (option->default_value) {
        char text[128];
        int len = snprintf(text, sizeof text, "(default %s)", option->default_value);
        print_word(out, text, len < (int)sizeof text ? (size_t)len : sizeof text - 1, &column);
    }
    fputc('\n', out);
}

void fc_options_print_help(FILE *out, const fc_option_table *table)
{
    for (size_t i = 0; i < table->count; i++)
        if (table->options[i].help)
            fc_options_print_option(out, &table->options[i]);
    static const fc_option help = {"-h, --help", NULL, NULL, "show this help", NULL};
    fc_options_print_option(out, &help);
}
