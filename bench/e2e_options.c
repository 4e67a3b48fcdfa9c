/* e2e_options.c — parsing fluidcast-e2e-bench's options. */
#include "e2e_options.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "fc_options.h"

const char *e2e_format_name(fc_image_format f)
{
    switch (f) {
    case FC_FORMAT_PNG: return "png";
    case FC_FORMAT_JPEG: return "jpeg";
    case FC_FORMAT_EXR: return "exr";
    case FC_FORMAT_RAW: return "raw";
    case FC_FORMAT_H264: return "h264";
    }
    return "?";
}

static int parse_count(const char *s, uint64_t *out)
{
    char *end;
    double v = strtod(s, &end);
    double unit = 1;
    if (*end == 'k' || *end == 'K')
        unit = 1024, end++;
    else if (*end == 'm' || *end == 'M')
        unit = 1024 * 1024, end++;
    if (end == s || *end || !(v >= 1) || v * unit > 16.0 * 1024 * 1024 * 1024)
        return 0;
    *out = (uint64_t)(v * unit);
    return 1;
}

static int parse_format(const char *s, fc_image_format *out)
{
    static const struct { const char *name; fc_image_format format; } names[] = {
        {"png", FC_FORMAT_PNG}, {"jpeg", FC_FORMAT_JPEG}, {"jpg", FC_FORMAT_JPEG},
        {"exr", FC_FORMAT_EXR}, {"raw", FC_FORMAT_RAW}};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
        if (strcmp(s, names[i].name) == 0) {
            *out = names[i].format;
            return 1;
        }
    return 0;
}

static int parse_size(const char *s, uint32_t out[2])
{
    unsigned w, h;
    char tail;
    if (sscanf(s, "%ux%u%c", &w, &h, &tail) != 2 || w < 1 || h < 1 || w > 16384 || h > 16384)
        return 0;
    out[0] = w, out[1] = h;
    return 1;
}

/* Splits a comma list into at most E2E_MAX_LIST items, each parsed by `item`. */
static fc_code parse_list(const char *option, const char *value, int *count, void *items, size_t item_size,
                          int (*item)(const char *, void *), fc_error *err)
{
    char buf[256];
    if (strlen(value) >= sizeof buf)
        return fc_error_set(err, FC_ERR_USAGE, "%s: list too long", option);
    strcpy(buf, value);
    *count = 0;
    for (char *save, *tok = strtok_r(buf, ",", &save); tok; tok = strtok_r(NULL, ",", &save)) {
        if (*count == E2E_MAX_LIST)
            return fc_error_set(err, FC_ERR_USAGE, "%s: at most %d items", option, E2E_MAX_LIST);
        if (!item(tok, (char *)items + item_size * (size_t)*count))
            return fc_error_set(err, FC_ERR_USAGE, "%s: bad item '%s'", option, tok);
        (*count)++;
    }
    if (*count == 0)
        return fc_error_set(err, FC_ERR_USAGE, "%s: empty list", option);
    return FC_OK;
}

static int count_item(const char *s, void *out) { return parse_count(s, out); }
static int size_item(const char *s, void *out) { return parse_size(s, out); }
static int format_item(const char *s, void *out) { return parse_format(s, out); }

static fc_code parse_number(const char *option, const char *value, double lo, double hi, double *out,
                            fc_error *err)
{
    char *end;
    double v = strtod(value, &end);
    if (end == value || *end || !(v >= lo && v <= hi))
        return fc_error_set(err, FC_ERR_USAGE, "%s: '%s' is not a number in %g..%g", option, value, lo, hi);
    *out = v;
    return FC_OK;
}

static e2e_options *as_options(void *target)
{
    return target;
}

static fc_code set_server(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name, (void)err;
    as_options(o)->server = value;
    return FC_OK;
}

static fc_code set_daemon(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name, (void)err;
    as_options(o)->daemon_path = value;
    return FC_OK;
}

static fc_code set_gpu(void *o, const char *name, const char *value, fc_error *err)
{
    if (strcmp(value, "software") != 0 && strcmp(value, "auto") != 0)
        return fc_error_set(err, FC_ERR_USAGE, "%s: '%s' is not software or auto", name, value);
    as_options(o)->gpu = value;
    return FC_OK;
}

static fc_code set_particles(void *target, const char *name, const char *value, fc_error *err)
{
    e2e_options *o = target;
    return parse_list(name, value, &o->n_particles, o->particles, sizeof o->particles[0], count_item, err);
}

static fc_code set_sizes(void *target, const char *name, const char *value, fc_error *err)
{
    e2e_options *o = target;
    return parse_list(name, value, &o->n_sizes, o->sizes, sizeof o->sizes[0], size_item, err);
}

static fc_code set_formats(void *target, const char *name, const char *value, fc_error *err)
{
    e2e_options *o = target;
    return parse_list(name, value, &o->n_formats, o->formats, sizeof o->formats[0], format_item, err);
}

static fc_code set_quality(void *o, const char *name, const char *value, fc_error *err)
{
    double v = 0;
    fc_code code = parse_number(name, value, 1, 100, &v, err);
    if (code == FC_OK)
        as_options(o)->quality = (uint32_t)v;
    return code;
}

static fc_code set_subsampling(void *o, const char *name, const char *value, fc_error *err)
{
    if (strcmp(value, "420") == 0)
        as_options(o)->stream_subsampling = FC_JPEG_SUBSAMPLING_YUV420;
    else if (strcmp(value, "444") == 0)
        as_options(o)->stream_subsampling = FC_JPEG_SUBSAMPLING_YUV444;
    else
        return fc_error_set(err, FC_ERR_USAGE, "%s: '%s' is not 420 or 444", name, value);
    return FC_OK;
}

static fc_code set_requests(void *o, const char *name, const char *value, fc_error *err)
{
    double v = 0;
    fc_code code = parse_number(name, value, 0, 1000000, &v, err);
    if (code == FC_OK)
        as_options(o)->requests = (int)v;
    return code;
}

static fc_code set_stream_seconds(void *o, const char *name, const char *value, fc_error *err)
{
    return parse_number(name, value, 0, 86400, &as_options(o)->stream_seconds, err);
}

static fc_code set_push_fps(void *o, const char *name, const char *value, fc_error *err)
{
    return parse_number(name, value, 0, 1e6, &as_options(o)->push_fps, err);
}

static fc_code set_density(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name, (void)value, (void)err;
    as_options(o)->density = 1;
    return FC_OK;
}

/* Every option with its help and default, in the order the usage lists them. */
static const fc_option options[] = {
    {"--server", "HOST:PORT", set_server, "use a running daemon instead of starting one", NULL},
    {"--daemon", "PATH", set_daemon, "fluidcastd to start (default: the one built with it)", NULL},
    {"--gpu", "software|auto", set_gpu, "passed to the started daemon", "software"},
    {"--particles", "LIST", set_particles, "particle counts, k/m suffixes (the H200 target: 1m)", "16k,64k"},
    {"--size", "LIST", set_sizes, "image sizes WxH", "640x360,1280x720"},
    {"--format", "LIST", set_formats, "jpeg, png, exr, raw", "jpeg,png"},
    {"--quality", "Q", set_quality, "JPEG quality 1..100", "90"},
    {"--stream-jpeg-subsampling", "420|444", set_subsampling,
     "the streaming viewer's JPEG chroma, 420 as fluidcast view asks", "420"},
    {"--requests", "N", set_requests, "timed requests per configuration, 0 = skip", "20"},
    {"--stream-seconds", "S", set_stream_seconds, "producer run per configuration, 0 = skip", "10"},
    {"--push-fps", "F", set_push_fps, "producer rate, 0 = as fast as the server accepts", "0"},
    {"--density", NULL, set_density, "frames carry a density per particle too, as SPH codes send them", NULL},
};

static const fc_option_table table = {"fluidcast-e2e-bench", options, sizeof options / sizeof options[0], NULL, NULL};

fc_code e2e_options_default(e2e_options *o, fc_error *err)
{
    *o = (e2e_options){0};
    return fc_options_set_defaults(&table, o, err);
}

void e2e_options_print_usage(void)
{
    printf("usage: fluidcast-e2e-bench [options]\n"
           "End-to-end loopback benchmark: particle upload -> image at the client, through a real fluidcastd.\n"
           "Prints markdown tables: request/response latency, the server's stage times, streaming throughput.\n");
    fc_options_print_help(stdout, &table);
    printf("A value may follow the option or an '='. Every configuration is particles x size x format.\n");
}

fc_code e2e_options_parse(int argc, char **argv, e2e_options *o, fc_error *err)
{
    bool help = false;
    fc_code code = fc_options_parse(&table, argc - 1, argv + 1, o, &help, err);
    o->help = help;
    return code;
}
