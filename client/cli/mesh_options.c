/* mesh_options.c — see mesh_options.h. */
#include "mesh_options.h"

#include <stdlib.h>
#include <string.h>

#include "cli_read_options.h"
#include "cli_report.h"
#include "cli_values.h"
#include "fc_error.h"
#include "fc_options.h"
#include "wire_surface.h"

static const struct {
    const char *name;
    uint32_t bit;
} attribute_names[] = {{"speed", FC_SURFACE_SPEED}, {"density", FC_SURFACE_DENSITY},
                       {"velocity", FC_SURFACE_VELOCITY}, {"id", FC_SURFACE_ID}};

static fc_code set_server(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name, (void)err;
    ((fc_mesh_options *)o)->server = value;
    return FC_OK;
}

static fc_code set_output(void *o, const char *name, const char *value, fc_error *err)
{
    if (value[0] == '\0')
        return fc_error_set(err, FC_ERR_USAGE, "%s needs a file name", name);
    ((fc_mesh_options *)o)->output = value;
    return FC_OK;
}

static fc_code set_start(void *o, const char *name, const char *value, fc_error *err)
{
    fc_mesh_options *m = o;
    m->range.has_start = true;
    return fc_cli_parse_uint(name, value, 0, UINT32_MAX, &m->range.start, err);
}

static fc_code set_end(void *o, const char *name, const char *value, fc_error *err)
{
    fc_mesh_options *m = o;
    m->range.has_end = true;
    return fc_cli_parse_uint(name, value, 0, UINT32_MAX, &m->range.end, err);
}

static fc_code set_step(void *o, const char *name, const char *value, fc_error *err)
{
    return fc_cli_parse_uint(name, value, 1, UINT32_MAX, &((fc_mesh_options *)o)->range.step, err);
}

static fc_code set_skip_existing(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name, (void)value, (void)err;
    ((fc_mesh_options *)o)->skip_existing = true;
    return FC_OK;
}

static fc_code attribute_bit(const char *word, size_t length, uint32_t *bit, fc_error *err)
{
    for (size_t i = 0; i < sizeof attribute_names / sizeof attribute_names[0]; i++)
        if (strlen(attribute_names[i].name) == length && strncmp(word, attribute_names[i].name, length) == 0) {
            *bit = attribute_names[i].bit;
            return FC_OK;
        }
    return fc_error_set(err, FC_ERR_USAGE, "--attributes: unknown attribute '%.*s' (speed, density, velocity, id, "
                        "all or none)", (int)length, word);
}

/* "speed,id", "all" or "none". */
static fc_code set_attributes(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name;
    fc_mesh_options *m = o;
    if (strcmp(value, "all") == 0 || strcmp(value, "none") == 0) {
        m->attributes = value[0] == 'a' ? FC_SURFACE_ATTRIBUTES_ALL : 0;
        return FC_OK;
    }
    m->attributes = 0;
    for (const char *word = value; *word;) {
        size_t length = strcspn(word, ",");
        uint32_t bit = 0;
        fc_code code = attribute_bit(word, length, &bit, err);
        if (code != FC_OK)
            return code;
        m->attributes |= bit;
        word += length + (word[length] == ',');
    }
    return FC_OK;
}

static fc_code set_read(void *o, const char *name, const char *value, fc_error *err)
{
    return fc_cli_set_read_option(&((fc_mesh_options *)o)->read, name, value, err);
}

static fc_code take_setting(void *o, int argc, char **argv, int *i, bool *known, fc_error *err)
{
    return fc_cli_take_setting(&((fc_mesh_options *)o)->settings, argc, argv, i, known, err);
}

static fc_code add_input(void *o, const char *arg, fc_error *err)
{
    fc_mesh_options *m = o;
    const char **grown = realloc(m->inputs, (m->input_count + 1) * sizeof *grown);
    if (!grown)
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for the input list");
    m->inputs = grown;
    m->inputs[m->input_count++] = arg;
    return FC_OK;
}

static const fc_option options[] = {
    {"-o", "OUT", set_output, NULL, NULL},
    {"--output", "OUT", set_output, NULL, NULL},
    {"--server", "HOST:PORT", set_server, NULL, NULL},
    {"--start", "N", set_start, NULL, NULL},
    {"--end", "N", set_end, NULL, NULL},
    {"--step", "N", set_step, NULL, NULL},
    {"--skip-existing", NULL, set_skip_existing, NULL, NULL},
    {"--attributes", "LIST", set_attributes, NULL, NULL},
    {"--dataset", "PATH", set_read, NULL, NULL},
    {"--select", "SELECTION", set_read, NULL, NULL},
};

static const fc_option_table table = {"fluidcast mesh", options, sizeof options / sizeof options[0], add_input,
                                      take_setting};

static fc_code check_combinations(fc_mesh_options *o, bool attributes_given, fc_error *err)
{
    if (o->input_count == 0)
        return fc_error_set(err, FC_ERR_USAGE, "mesh needs particle files: a list, a glob, a %%04d or a {} pattern");
    if (!o->output)
        return fc_error_set(err, FC_ERR_USAGE, "mesh needs an output: -o OUT.ply|.obj|.vtp|.stl or a %%04d pattern");
    fc_code code = fc_mesh_file_format_of(o->output, &o->format, err);
    if (code != FC_OK)
        return code;
    bool carries = o->format == FC_MESH_FILE_PLY || o->format == FC_MESH_FILE_VTP;
    if (!carries && attributes_given && o->attributes != 0)
        return fc_error_set(err, FC_ERR_USAGE, "--attributes: %s has no place for them (.ply and .vtp have)",
                            o->output);
    if (!carries)
        o->attributes = 0;
    return FC_OK;
}

fc_code fc_mesh_parse(int argc, char **argv, fc_mesh_options *out, fc_error *err)
{
    memset(out, 0, sizeof *out);
    out->server = FC_DEFAULT_SERVER;
    out->range.step = 1;
    out->attributes = FC_SURFACE_ATTRIBUTES_ALL;
    fc_cli_settings_init(&out->settings);
    bool attributes_given = false;
    for (int i = 0; i < argc; i++)
        attributes_given = attributes_given || fc_option_matches(argv[i], "--attributes");
    fc_code code = fc_options_parse(&table, argc, argv, out, &out->help, err);
    if (code != FC_OK || out->help)
        return code;
    return check_combinations(out, attributes_given, err);
}

void fc_mesh_options_free(fc_mesh_options *o)
{
    free(o->inputs);
    o->inputs = NULL;
    o->input_count = 0;
}

void fc_mesh_print_help(FILE *to)
{
    fputs("usage: fluidcast mesh INPUTS... -o OUT [options]\n"
          "\n"
          "Extracts the surface of the fluid in particle files as a triangle mesh on a\n"
          "fluidcastd server (PROTOCOL.md section 13) and writes it to OUT: .ply (binary)\n"
          "and .vtp (VTK XML) with the normals and the attributes, .obj with the normals,\n"
          ".stl (binary) with face normals. The surface_* options below shape the mesh.\n"
          "\n"
          "INPUTS: as for render: files in order, quoted globs, one %d or {} pattern.\n"
          "\n"
          "  -o, --output OUT        the mesh file; for several inputs a pattern with one\n"
          "                          %d (meshes/surface_%04d.ply), numbered like the\n"
          "                          input pattern's frames, else 0, 1, 2... (a\n"
          "                          missing directory is made)\n"
          "  --server HOST:PORT      server address (default " FC_DEFAULT_SERVER ")\n"
          "  --start N, --end N      first and last frame number of a %d or {} pattern\n"
          "  --step N                every Nth frame of a pattern (default 1)\n"
          "  --skip-existing         leave frames whose mesh file exists\n"
          "  --attributes LIST       per-vertex attributes for .ply/.vtp: speed, density,\n"
          "                          velocity, id, comma-separated, all or none (default\n"
          "                          all the frame can give: speed and velocity need\n"
          "                          velocities, density densities, id ids)\n"
          "\n",
          to);
    fc_cli_print_read_options_help(to, true);
    fc_settings defaults;
    fc_settings_default(&defaults);
    fc_cli_print_settings_help(to, &defaults);
    fputs("On a terminal a progress bar shows frames and the time left; otherwise one\n"
          "line per frame.\n"
          "  -h, --help              show this help\n"
          "\n",
          to);
    fc_cli_print_exit_codes(to);
}
