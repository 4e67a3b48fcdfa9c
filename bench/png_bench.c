/* png_bench.c — fluidcast-png-bench: the daemon's PNG writer (png_encoder.h)
 * timed on real images at several zlib levels and thread counts, in memory.
 *
 * Every configuration encodes every image once per round, rounds interleaved
 * (a shared machine's load falls on all of them alike); per image the median
 * wall time and the median CPU time of the process (all threads) count. */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "fc_error.h"
#include "fc_file.h"
#include "fc_options.h"
#include "image_decoder.h"
#include "png_encoder.h"

enum { MAX_LIST = 16, MAX_IMAGES = 256 };

typedef struct png_bench_options {
    unsigned threads[MAX_LIST];
    unsigned n_threads;
    uint32_t levels[MAX_LIST];
    unsigned n_levels;
    unsigned rounds;
    uint32_t channels;   /* 4, or 3 (alpha dropped) */
    uint32_t synthetic_w, synthetic_h;
    const char *files[MAX_IMAGES];
    unsigned n_files;
} png_bench_options;

static void usage(void)
{
    printf("usage: fluidcast-png-bench [--threads LIST] [--level LIST] [--rounds N] [--rgb] FILE.png...\n"
           "       fluidcast-png-bench [...] --synthetic WxH\n"
           "Times fluidcastd's PNG writer (rows in strips deflated on several threads) on each\n"
           "image, decoded to 8-bit RGBA first (--rgb: alpha dropped), in memory.\n"
           "  --threads LIST   thread counts, 0 = automatic (default 1,2,4,8,0)\n"
           "  --level LIST     zlib levels 0..9 (default 4, fluidcastd's default)\n"
           "  --rounds N       encodes of every image per configuration (default 7): medians\n"
           "  --synthetic WxH  one generated image (a gradient with noise) instead of files\n"
           "Prints a markdown table: per image, median wall ms, MB/s of RGBA/RGB bytes,\n"
           "median CPU ms of all threads, bytes, and the speed-up over the first thread count.\n");
}

static unsigned parse_list(const char *s, unsigned max_value, unsigned *out)
{
    unsigned n = 0;
    while (*s && n < MAX_LIST) {
        char *end;
        unsigned long v = strtoul(s, &end, 10);
        if (end == s || v > max_value)
            return 0;
        out[n++] = (unsigned)v;
        s = *end == ',' ? end + 1 : end;
        if (end == s && *s)
            return 0;
    }
    return n;
}

static double clock_ms(clockid_t clock)
{
    struct timespec t;
    clock_gettime(clock, &t);
    return t.tv_sec * 1e3 + t.tv_nsec / 1e6;
}

static int compare_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double median(double *v, unsigned n)
{
    qsort(v, n, sizeof *v, compare_double);
    return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

/* Reads and decodes one file to 8-bit rows of `channels`. */
static int load_image(const char *path, uint32_t channels, fc_png_rows *rows)
{
    uint8_t *bytes = NULL;
    size_t size = 0;
    fc_error err;
    if (fc_read_file(path, SIZE_MAX, &bytes, &size, &err) != FC_OK) {
        fprintf(stderr, "fluidcast-png-bench: %s\n", err.message);
        return 0;
    }
    fc_image img = {0};
    int ok = fc_decode_image_bytes(bytes, size, 65536, &img, &err) == FC_OK && img.type == FC_PIXEL_U8;
    free(bytes);
    if (!ok) {
        fprintf(stderr, "fluidcast-png-bench: %s: not an 8-bit image\n", path);
        free(img.pixels);
        return 0;
    }
    *rows = (fc_png_rows){img.pixels, img.width, img.height, channels, 4};   /* RGB: alpha read past */
    return 1;
}

/* A gradient with noise in its low bits: compressible like a render, not trivially. */
static fc_png_rows synthetic(uint32_t w, uint32_t h, uint32_t channels)
{
    size_t n = (size_t)w * h * channels;
    uint8_t *px = malloc(n);
    uint32_t state = 1;
    for (size_t i = 0; px && i < n; i++) {
        state = state * 1664525u + 1013904223u;
        size_t pixel = i / channels;
        px[i] = (uint8_t)((pixel % w) * 3 + (pixel / w) * 2 + (i % channels) * 50 + ((state >> 29) & 3));
    }
    return (fc_png_rows){px, w, h, channels, 0};
}

static fc_code set_rgb(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name, (void)value, (void)err;
    ((png_bench_options *)o)->channels = 3;
    return FC_OK;
}

static fc_code set_threads(void *target, const char *name, const char *value, fc_error *err)
{
    png_bench_options *o = target;
    o->n_threads = parse_list(value, 64, o->threads);
    return o->n_threads ? FC_OK : fc_error_set(err, FC_ERR_USAGE, "%s '%s': expected counts 0..64", name, value);
}

static fc_code set_levels(void *target, const char *name, const char *value, fc_error *err)
{
    png_bench_options *o = target;
    o->n_levels = parse_list(value, 9, o->levels);
    return o->n_levels ? FC_OK : fc_error_set(err, FC_ERR_USAGE, "%s '%s': expected levels 0..9", name, value);
}

static fc_code set_rounds(void *o, const char *name, const char *value, fc_error *err)
{
    unsigned one[MAX_LIST];
    if (parse_list(value, 1000, one) != 1 || one[0] == 0)
        return fc_error_set(err, FC_ERR_USAGE, "%s '%s': expected a number 1..1000", name, value);
    ((png_bench_options *)o)->rounds = one[0];
    return FC_OK;
}

static fc_code set_synthetic(void *target, const char *name, const char *value, fc_error *err)
{
    png_bench_options *o = target;
    char tail;
    if (sscanf(value, "%ux%u%c", &o->synthetic_w, &o->synthetic_h, &tail) != 2 || o->synthetic_w == 0 ||
        o->synthetic_h == 0)
        return fc_error_set(err, FC_ERR_USAGE, "%s '%s': expected WIDTHxHEIGHT", name, value);
    return FC_OK;
}

static fc_code add_file(void *target, const char *arg, fc_error *err)
{
    png_bench_options *o = target;
    if (o->n_files == MAX_IMAGES)
        return fc_error_set(err, FC_ERR_USAGE, "at most %d images", MAX_IMAGES);
    o->files[o->n_files++] = arg;
    return FC_OK;
}

/* The options; their help is usage()'s. */
static const fc_option options[] = {
    {"--threads", "LIST", set_threads, NULL, NULL},
    {"--level", "LIST", set_levels, NULL, NULL},
    {"--rounds", "N", set_rounds, NULL, NULL},
    {"--rgb", NULL, set_rgb, NULL, NULL},
    {"--synthetic", "WxH", set_synthetic, NULL, NULL},
};

static const fc_option_table table = {"fluidcast-png-bench", options, sizeof options / sizeof options[0],
                                      add_file, NULL};

/* Options over the defaults. *done when there is nothing to run: then the
 * exit status is returned (0 after --help, 2 for a usage error). */
static int parse_args(int argc, char **argv, png_bench_options *o, bool *done)
{
    *o = (png_bench_options){.threads = {1, 2, 4, 8, 0}, .n_threads = 5, .levels = {4}, .n_levels = 1, .rounds = 7,
                             .channels = 4};
    bool help = false;
    fc_error err;
    *done = true;
    if (fc_options_parse(&table, argc - 1, argv + 1, o, &help, &err) != FC_OK) {
        fprintf(stderr, "fluidcast-png-bench: %s\n", err.message);
        return 2;
    }
    if (help || (o->n_files == 0 && o->synthetic_w == 0)) {
        usage();
        return help ? 0 : 2;
    }
    *done = false;
    return 0;
}

/* One configuration's medians, summed over the images. */
typedef struct png_bench_row {
    double wall_ms, cpu_ms;
    size_t bytes;
} png_bench_row;

static int run(const png_bench_options *o, const fc_png_rows *images, unsigned n_images, uint32_t level,
               png_bench_row *rows)
{
    unsigned configs = o->n_threads;
    double *wall = calloc((size_t)configs * n_images * o->rounds, sizeof *wall);
    double *cpu = calloc((size_t)configs * n_images * o->rounds, sizeof *cpu);
    fc_buf out;
    fc_buf_init(&out);
    int ok = wall && cpu;
    for (unsigned r = 0; ok && r < o->rounds; r++) {
        for (unsigned c = 0; ok && c < configs; c++) {
            for (unsigned i = 0; ok && i < n_images; i++) {
                fc_error err;
                fc_buf_reset(&out);
                double w0 = clock_ms(CLOCK_MONOTONIC), c0 = clock_ms(CLOCK_PROCESS_CPUTIME_ID);
                ok = fc_png_encode(&images[i], level, o->threads[c], &out, &err) == FC_OK;
                size_t at = ((size_t)c * n_images + i) * o->rounds + r;
                wall[at] = clock_ms(CLOCK_MONOTONIC) - w0;
                cpu[at] = clock_ms(CLOCK_PROCESS_CPUTIME_ID) - c0;
                if (!ok)
                    fprintf(stderr, "fluidcast-png-bench: %s\n", err.message);
                if (r == 0)
                    rows[c].bytes += out.len;
            }
        }
    }
    for (unsigned c = 0; ok && c < configs; c++) {
        for (unsigned i = 0; i < n_images; i++) {
            size_t at = ((size_t)c * n_images + i) * o->rounds;
            rows[c].wall_ms += median(wall + at, o->rounds);
            rows[c].cpu_ms += median(cpu + at, o->rounds);
        }
    }
    fc_buf_free(&out);
    free(wall);
    free(cpu);
    return ok;
}

static void print_rows(const png_bench_options *o, unsigned n_images, size_t pixel_bytes, uint32_t level,
                       const png_bench_row *rows)
{
    for (unsigned c = 0; c < o->n_threads; c++) {
        char threads[32];
        if (o->threads[c] == 0)
            snprintf(threads, sizeof threads, "auto (%u)", fc_png_default_threads());
        else
            snprintf(threads, sizeof threads, "%u", o->threads[c]);
        printf("| %u | %s | %u | %.2f | %.1f | %.2f | %zu | %.2f |\n", level, threads, n_images,
               rows[c].wall_ms / n_images, pixel_bytes / 1e3 / rows[c].wall_ms, rows[c].cpu_ms / n_images,
               rows[c].bytes / n_images, rows[0].wall_ms / rows[c].wall_ms);
    }
}

int main(int argc, char **argv)
{
    png_bench_options o;
    bool done;
    int status = parse_args(argc, argv, &o, &done);
    if (done)
        return status;
    fc_png_rows images[MAX_IMAGES];
    unsigned n = 0;
    size_t pixel_bytes = 0;
    if (o.synthetic_w)
        images[n++] = synthetic(o.synthetic_w, o.synthetic_h, o.channels);
    for (unsigned i = 0; i < o.n_files && n < MAX_IMAGES; i++)
        if (load_image(o.files[i], o.channels, &images[n]))
            n++;
    for (unsigned i = 0; i < n; i++)
        pixel_bytes += (size_t)images[i].width * images[i].height * images[i].channels;
    if (n == 0 || !images[0].pixels)
        return 1;
    printf("fluidcast-png-bench: %u image(s), %zu bytes of pixels, %u channels, %ld online cores, %u rounds\n\n", n,
           pixel_bytes, o.channels, sysconf(_SC_NPROCESSORS_ONLN), o.rounds);
    printf("| level | threads | images | wall ms per image | MB/s | CPU ms per image | bytes per image | speed-up |\n");
    printf("|---|---|---|---|---|---|---|---|\n");
    for (unsigned l = 0; l < o.n_levels && status == 0; l++) {
        png_bench_row rows[MAX_LIST] = {{0}};
        if (!run(&o, images, n, o.levels[l], rows))
            status = 1;
        else
            print_rows(&o, n, pixel_bytes, o.levels[l], rows);
    }
    for (unsigned i = 0; i < n; i++)
        free((void *)images[i].pixels);
    return status;
}
