/* cli_setting_options.h — the render settings' command-line options, made
 * from the settings table (fc_settings.h): each setting's option, how its value
 * is written, its checks and its help line come from its entry, so every
 * command that renders (snapshot, render, stream, view) takes the same options
 * and a new setting needs nothing here. */
#ifndef FC_CLI_SETTING_OPTIONS_H
#define FC_CLI_SETTING_OPTIONS_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "fc_settings.h"

/* A command's settings and which of them the user gave. */
typedef struct fc_cli_settings {
    fc_settings values;
    uint64_t given;          /* bit `key` set: the option of the setting with that key was given */
} fc_cli_settings;

/* The settings a command starts from: fc_settings_default, nothing given. */
void fc_cli_settings_init(fc_cli_settings *s);

/* Whether the user gave the setting called `name` (a field name, "colormap"). */
bool fc_cli_setting_given(const fc_cli_settings *s, const char *name);

/* Takes argv[*i] when it is a render setting's option ("--ior 1.5" or
 * "--ior=1.5", moving *i past a value in the next argument), as
 * fc_options_take does: *known false, and nothing done, when it is not one. */
fc_code fc_cli_take_setting(fc_cli_settings *s, int argc, char **argv, int *i, bool *known, fc_error *err);

/* Parses `value` as the setting's option and stores it: FC_ERR_USAGE naming the
 * option when it is malformed or outside the setting's domain. A settings
 * whose default depends on the smoothing (iterations) follows a new
 * --smoothing unless it was given itself. */
fc_code fc_cli_set_setting(fc_cli_settings *s, const fc_setting_spec *spec, const char *value, fc_error *err);

/* Prints every setting's option under its group's heading, each with its
 * domain and its default as `defaults` holds it (a command may start from
 * other defaults than fc_settings_default). */
void fc_cli_print_settings_help(FILE *to, const fc_settings *defaults);

#endif
