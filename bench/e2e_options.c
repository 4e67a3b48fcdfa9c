/* e2e_options.c — parsing fluidcast-e2e-bench's options. */
#include "e2e_options.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"

void e2e_options_default(e2e_options *o)
{
    *o = (e2e_options){.gpu = "software",
                       .particles = {16384, 65536},
                       .n_particles = 2,
                       .sizes = {{640, 360}, {1280, 720}},
                       .n_sizes = 2,
                       .formats = {FC_FORMAT_JPEG, FC_FORMAT_PNG},
                       .n_formats = 2,
                       .quality = 90,
                       .stream_subsampling = FC_JPEG_SUBSAMPLING_YUV420,
                       .requests = 20,
                       .stream_seconds = 10.0};
}

void e2e_options_print_usage(void)
{
    printf("usage: fluidcast-e2e-bench [options]\n"
           "End-to-end loopback benchmark: particle upload -> image at the client, through a real fluidcastd.\n"
           "Prints markdown tables: request/response latency, the server's stage times, streaming throughput.\n"
           "  --server HOST:PORT     use a running daemon instead of starting one\n"
           "  --daemon PATH          fluidcastd to start (default: the one built with it)\n"
           "  --gpu software|auto    passed to the started daemon (default software)\n"
           "  --particles LIST       particle counts, k/m suffixes (default 16k,64k; the H200 target: 1m)\n"
           "  --size LIST            image sizes WxH (default 640x360,1280x720)\n"
           "  --format LIST          jpeg, png, exr, raw (default jpeg,png)\n"
           "  --quality Q            JPEG quality 1..100 (default 90)\n"
           "  --stream-jpeg-subsampling 420|444\n"
           "                         the streaming viewer's JPEG chroma (default 420, as fluidcast view)\n"
           "  --requests N           timed requests per configuration, 0 = skip (default 20)\n"
           "  --stream-seconds S     producer run per configuration, 0 = skip (default 10)\n"
           "  --push-fps F           producer rate, 0 = as fast as the server accepts (default 0)\n"
           "  --density              frames carry a density per particle too, as SPH codes send them\n"
           "  --help                 this text\n"
           "A value may follow the option or an '='. Every configuration is particles x size x format.\n");
}

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

static fc_code apply_option(const char *name, const char *value, e2e_options *o, fc_error *err)
{
    double v = 0;
    fc_code code = FC_OK;
    if (strcmp(name, "--server") == 0)
        o->server = value;
    else if (strcmp(name, "--daemon") == 0)
        o->daemon_path = value;
    else if (strcmp(name, "--gpu") == 0) {
        if (strcmp(value, "software") != 0 && strcmp(value, "auto") != 0)
            return fc_error_set(err, FC_ERR_USAGE, "--gpu: '%s' is not software or auto", value);
        o->gpu = value;
    } else if (strcmp(name, "--particles") == 0)
        code = parse_list(name, value, &o->n_particles, o->particles, sizeof o->particles[0], count_item, err);
    else if (strcmp(name, "--size") == 0)
        code = parse_list(name, value, &o->n_sizes, o->sizes, sizeof o->sizes[0], size_item, err);
    else if (strcmp(name, "--format") == 0)
        code = parse_list(name, value, &o->n_formats, o->formats, sizeof o->formats[0], format_item, err);
    else if (strcmp(name, "--quality") == 0) {
        if ((code = parse_number(name, value, 1, 100, &v, err)) == FC_OK)
            o->quality = (uint32_t)v;
    } else if (strcmp(name, "--stream-jpeg-subsampling") == 0) {
        if (strcmp(value, "420") == 0)
            o->stream_subsampling = FC_JPEG_SUBSAMPLING_YUV420;
        else if (strcmp(value, "444") == 0)
            o->stream_subsampling = FC_JPEG_SUBSAMPLING_YUV444;
        else
            return fc_error_set(err, FC_ERR_USAGE, "%s: '%s' is not 420 or 444", name, value);
    } else if (strcmp(name, "--requests") == 0) {
        if ((code = parse_number(name, value, 0, 1000000, &v, err)) == FC_OK)
            o->requests = (int)v;
    } else if (strcmp(name, "--stream-seconds") == 0)
        code = parse_number(name, value, 0, 86400, &o->stream_seconds, err);
    else if (strcmp(name, "--push-fps") == 0)
        code = parse_number(name, value, 0, 1e6, &o->push_fps, err);
    else
        return fc_error_set(err, FC_ERR_USAGE, "unknown option '%s'", name);
    return code;
}

fc_code e2e_options_parse(int argc, char **argv, e2e_options *o, fc_error *err)
{
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            o->help = 1;
            continue;
        }
        if (strcmp(argv[i], "--density") == 0) {
            o->density = 1;
            continue;
        }
        char name[64];
        const char *eq = strchr(argv[i], '=');
        const char *value;
        if (eq && (size_t)(eq - argv[i]) < sizeof name) {
            snprintf(name, sizeof name, "%.*s", (int)(eq - argv[i]), argv[i]);
            value = eq + 1;
        } else {
            if (i + 1 >= argc)
                return fc_error_set(err, FC_ERR_USAGE, "%s needs a value", argv[i]);
            snprintf(name, sizeof name, "%s", argv[i]);
            value = argv[++i];
        }
        fc_code code = apply_option(name, value, o, err);
        if (code != FC_OK)
            return code;
    }
    return FC_OK;
}
