/* fc_options.h — one table-driven command-line parser for every program of
 * the project (fluidcastd, the fluidcast subcommands, the benchmarks).
 *
 * A program lists its options in a table of fc_option rows: the name, the
 * name of its value (none for a flag), the setter that stores it, the help
 * text and the default, each written once. The parser accepts
 * "--name value", "--name=value", flags without a value, positional arguments
 * (when the table takes them) and -h/--help; the help lists the rows. */
#ifndef FC_OPTIONS_H
#define FC_OPTIONS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "fluidcast_types.h"

/* Applies one option to the program's options struct (`target`); value is NULL
 * for a flag. Returns FC_ERR_USAGE naming the option for a value it refuses. */
typedef fc_code (*fc_option_setter)(void *target, const char *name, const char *value, fc_error *err);

typedef struct fc_option {
    const char *name;            /* "--session" */
    const char *value_name;      /* "ID": the option takes a value, shown as "--session ID"; NULL: a flag */
    fc_option_setter set;
    const char *help;            /* the help text, one paragraph (wrapped when printed); NULL: not listed */
    const char *default_value;   /* set by fc_options_set_defaults and shown as "(default X)"; NULL: none */
} fc_option;

typedef struct fc_option_table {
    const char *program;         /* "fluidcastd", "fluidcast stream": named in usage errors */
    const fc_option *options;
    size_t count;
    /* Takes one positional argument; NULL: positional arguments are refused. */
    fc_code (*positional)(void *target, const char *arg, fc_error *err);
    /* Options beyond the rows, from a table of their own (a command's render
     * settings): takes argv[*i] as fc_options_take does, with *known false when
     * it is none of them. NULL: the rows are all. */
    fc_code (*more)(void *target, int argc, char **argv, int *i, bool *known, fc_error *err);
} fc_option_table;

/* Parses argv[0..argc) (the arguments only, no program name) into target. A
 * "-h" or "--help" stops parsing with *help true. FC_ERR_USAGE, naming the
 * argument: "unknown option --x (see PROGRAM --help)", "--x needs a value",
 * "--x takes no value", "unexpected argument \"x\" (see PROGRAM --help)";
 * else the first error of a setter. */
fc_code fc_options_parse(const fc_option_table *table, int argc, char **argv, void *target, bool *help,
                         fc_error *err);

/* Takes the option at argv[*i], with its value (after '=' or the next
 * argument, then *i moves past it), when the table has it: for a program that
 * tries several tables in turn. *known false, and nothing done, when it has
 * not. FC_ERR_USAGE "--x needs a value", "--x takes no value"; else the
 * setter's result. */
fc_code fc_options_take(const fc_option_table *table, int argc, char **argv, int *i, void *target, bool *known,
                        fc_error *err);

/* Hands every row's default_value to its setter, in table order. */
fc_code fc_options_set_defaults(const fc_option_table *table, void *target, fc_error *err);

/* The row `arg` names, as "--name" or "--name=value" (then *inline_value
 * points at the value, else it is NULL); NULL when none does. */
const fc_option *fc_options_find(const fc_option_table *table, const char *arg, const char **inline_value);

/* Whether arg is "--name" or "--name=..." for this name. */
bool fc_option_matches(const char *arg, const char *name);

/* One row's block: "  --name VALUE", then its help text and "(default X)"
 * wrapped to 80 columns from column 26. */
void fc_options_print_option(FILE *out, const fc_option *option);

/* One block per listed row: "  --name VALUE" and its help text with
 * "(default X)", wrapped to 80 columns from column 26; then -h, --help. */
void fc_options_print_help(FILE *out, const fc_option_table *table);

#endif
