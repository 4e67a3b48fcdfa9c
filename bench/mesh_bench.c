/* mesh_bench.c — fluidcast-mesh-bench: surface mesh extraction
 * (fc_surface_extract, issue 27) on the drop scene (bench/scene.h) at several
 * particle counts and cell sizes: wall time of each extraction (the GL queue
 * drained by the readback), the best of --repeat, and particles meshed per
 * second, with the mesh's vertices, triangles and a digest of its bytes (--frame meshes a
 * gen_particles.py file instead of the scene). bench/RESULTS.md keeps the
 * figures; bench/gpu_check.sh runs it on a lent GPU. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "egl_context.h"
#include "fc_error.h"
#include "fc_frame.h"
#include "fc_options.h"
#include "fc_settings.h"
#include "pipeline.h"
#include "scene.h"
#include "surface_extract.h"

enum { MAX_LIST = 8 };

typedef struct mesh_bench_options {
    uint64_t particles[MAX_LIST];
    int n_particles;
    float cells[MAX_LIST];
    int n_cells;
    int repeat;
    uint32_t smoothing;
    fc_surface_kernel kernel;
    fc_gpu_choice gpu;
    char frame_path[1024];   /* a raw float32 x y z file meshed instead of the drop scene; empty: the scene */
    float radius;            /* the file's particle radius */
} mesh_bench_options;

static fc_code set_particles(void *target, const char *name, const char *value, fc_error *err)
{
    mesh_bench_options *o = target;
    o->n_particles = 0;
    for (const char *p = value; *p && o->n_particles < MAX_LIST;) {
        char *end;
        unsigned long long n = strtoull(p, &end, 10);
        if (end == p || n == 0)
            return fc_error_set(err, FC_ERR_USAGE, "%s: \"%s\" is not a list of counts", name, value);
        o->particles[o->n_particles++] = n;
        p = *end == ',' ? end + 1 : end;
        if (*end && *end != ',')
            return fc_error_set(err, FC_ERR_USAGE, "%s: \"%s\" is not a list of counts", name, value);
    }
    return FC_OK;
}

static fc_code set_cells(void *target, const char *name, const char *value, fc_error *err)
{
    mesh_bench_options *o = target;
    o->n_cells = 0;
    for (const char *p = value; *p && o->n_cells < MAX_LIST;) {
        char *end;
        float c = strtof(p, &end);
        if (end == p || !(c > 0.25f && c <= 4.0f) || (*end && *end != ','))
            return fc_error_set(err, FC_ERR_USAGE, "%s: \"%s\" is not a list of cells in (0.25, 4]", name, value);
        o->cells[o->n_cells++] = c;
        p = *end == ',' ? end + 1 : end;
    }
    return FC_OK;
}

static fc_code set_repeat(void *target, const char *name, const char *value, fc_error *err)
{
    int n = atoi(value);
    if (n < 1 || n > 100)
        return fc_error_set(err, FC_ERR_USAGE, "%s: %s is not in 1..100", name, value);
    ((mesh_bench_options *)target)->repeat = n;
    return FC_OK;
}

static fc_code set_smoothing(void *target, const char *name, const char *value, fc_error *err)
{
    int n = atoi(value);
    if (n < 0 || n > 100)
        return fc_error_set(err, FC_ERR_USAGE, "%s: %s is not in 0..100", name, value);
    ((mesh_bench_options *)target)->smoothing = (uint32_t)n;
    return FC_OK;
}

static fc_code set_kernel(void *target, const char *name, const char *value, fc_error *err)
{
    const fc_setting_spec *spec = fc_setting_by_name("surface_kernel");
    for (uint32_t i = 0; i < fc_setting_choice_count(spec); i++)
        if (strcmp(spec->choices[i], value) == 0) {
            ((mesh_bench_options *)target)->kernel = (fc_surface_kernel)i;
            return FC_OK;
        }
    return fc_error_set(err, FC_ERR_USAGE, "%s: unknown kernel \"%s\"", name, value);
}

static fc_code set_gpu(void *target, const char *name, const char *value, fc_error *err)
{
    (void)name;
    return fc_gpu_choice_parse(value, &((mesh_bench_options *)target)->gpu, err);
}

static fc_code set_frame(void *target, const char *name, const char *value, fc_error *err)
{
    mesh_bench_options *o = target;
    if (strlen(value) >= sizeof o->frame_path)
        return fc_error_set(err, FC_ERR_USAGE, "%s: the path is too long", name);
    strcpy(o->frame_path, value);
    return FC_OK;
}

static fc_code set_radius(void *target, const char *name, const char *value, fc_error *err)
{
    char *end;
    float r = strtof(value, &end);
    if (end == value || *end || !(r > 0.0f && r < 1e6f))
        return fc_error_set(err, FC_ERR_USAGE, "%s: %s is not a radius", name, value);
    ((mesh_bench_options *)target)->radius = r;
    return FC_OK;
}

static const fc_option rows[] = {
    {"--particles", "N,...", set_particles, "particle counts of the drop scene", "65536"},
    {"--cells", "C,...", set_cells, "grid cells in particle radii", "0.5,1,1.5"},
    {"--repeat", "K", set_repeat, "extractions per point; the fastest is reported", "3"},
    {"--smoothing", "N", set_smoothing, "Taubin steps", "0"},
    {"--kernel", "K", set_kernel, "metaball, sph or anisotropic", "metaball"},
    {"--gpu", "DEVICE", set_gpu, "auto, software or an EGL device index (fluidcastd --gpu)", "software"},
    {"--frame", "FILE.f32", set_frame, "mesh this raw float32 x y z file instead of the drop scene (needs --radius)",
     NULL},
    {"--radius", "R", set_radius, "the --frame file's particle radius", NULL},
};
static const fc_option_table table = {"fluidcast-mesh-bench", rows, sizeof rows / sizeof rows[0], NULL, NULL};

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

/* FNV-1a over bytes, continuing from `h`. */
static uint64_t fnv1a(uint64_t h, const void *data, size_t bytes)
{
    const unsigned char *p = data;
    for (size_t i = 0; i < bytes; i++)
        h = (h ^ p[i]) * 0x100000001b3ull;
    return h;
}

/* A digest of the mesh's positions, normals and triangles: equal digests before and after a change to the
 * extraction say it kept the mesh byte for byte. */
static uint64_t mesh_digest(const fc_surface_mesh *m)
{
    uint64_t h = fnv1a(0xcbf29ce484222325ull, m->positions, (size_t)m->vertex_count * 12);
    h = fnv1a(h, m->normals, (size_t)m->vertex_count * 12);
    return fnv1a(h, m->indices, (size_t)m->triangle_count * 12);
}

static fc_code bench_point(fc_pipeline *pipe, const fc_frame *frame, float radius, float cell,
                           const mesh_bench_options *o, fc_error *err)
{
    fc_settings s;
    fc_settings_default(&s);
    s.radius = radius;
    s.surface_cell = cell;
    s.surface_kernel = o->kernel;
    s.surface_smoothing = o->smoothing;
    double best = 1e30;
    fc_surface_mesh m = {0};
    for (int r = 0; r < o->repeat; r++) {
        fc_surface_mesh_free(&m);
        double start = now_s();
        fc_code code = fc_surface_extract(pipe, frame, &s, &m, err);
        double t = now_s() - start;
        if (code != FC_OK)
            return code;
        best = t < best ? t : best;
    }
    printf("%10llu %6.2f %10u %10u %10.1f %14.0f %016llx\n", (unsigned long long)frame->count, (double)cell,
           m.vertex_count, m.triangle_count, best * 1e3, (double)frame->count / best,
           (unsigned long long)mesh_digest(&m));
    fflush(stdout);
    fc_surface_mesh_free(&m);
    return FC_OK;
}

/* The particles of a raw float32 x y z file (gen_particles.py's .f32). */
static fc_code read_frame(const char *path, fc_frame *frame, fc_error *err)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return fc_error_set(err, FC_ERR_IO, "cannot open %s", path);
    long bytes = fseek(f, 0, SEEK_END) == 0 ? ftell(f) : -1;
    fc_code code = bytes > 0 && bytes % 12 == 0 ? FC_OK
                                                : fc_error_set(err, FC_ERR_USAGE, "%s is not float32 x y z", path);
    if (code == FC_OK)
        code = fc_frame_alloc(frame, (uint64_t)bytes / 12, 0, err);
    rewind(f);
    if (code == FC_OK && fread(frame->positions, 12, frame->count, f) != frame->count)
        code = fc_error_set(err, FC_ERR_IO, "cannot read %s", path);
    fclose(f);
    return code;
}

/* Every cell size on one frame. */
static fc_code bench_frame(fc_pipeline *pipe, const fc_frame *frame, float radius, const mesh_bench_options *o,
                           fc_error *err)
{
    fc_code code = FC_OK;
    for (int c = 0; code == FC_OK && c < o->n_cells; c++)
        code = bench_point(pipe, frame, radius, o->cells[c], o, err);
    return code;
}

static fc_code run(const mesh_bench_options *o, fc_error *err)
{
    fc_gl_context *ctx = NULL;
    fc_pipeline *pipe = NULL;
    fc_code code = fc_gl_context_create(&o->gpu, &ctx, err);
    if (code == FC_OK) {
        printf("GL_RENDERER: %s; kernel %s, smoothing %u, best of %d\n\n", fc_gl_context_renderer(ctx),
               fc_setting_by_name("surface_kernel")->choices[o->kernel], o->smoothing, o->repeat);
        printf("%10s %6s %10s %10s %10s %14s %16s\n", "particles", "cell", "vertices", "triangles", "ms", "particles/s",
               "mesh digest");
        code = fc_pipeline_create(NULL, &pipe, err);
    }
    if (code == FC_OK && o->frame_path[0]) {
        fc_frame frame = {0};
        code = read_frame(o->frame_path, &frame, err);
        if (code == FC_OK)
            code = bench_frame(pipe, &frame, o->radius, o, err);
        fc_frame_free(&frame);
    }
    for (int i = 0; code == FC_OK && !o->frame_path[0] && i < o->n_particles; i++) {
        fc_frame frame = {0};
        float spacing;
        code = bench_scene_drop(o->particles[i], &frame, &spacing, err);
        if (code == FC_OK)
            code = bench_frame(pipe, &frame, spacing * BENCH_SCENE_RADIUS_PER_SPACING, o, err);
        fc_frame_free(&frame);
    }
    if (pipe)
        fc_pipeline_destroy(pipe);
    fc_gl_context_destroy(ctx);
    return code;
}

int main(int argc, char **argv)
{
    mesh_bench_options o = {0};
    fc_error err = {0};
    bool help = false;
    fc_code code = fc_options_set_defaults(&table, &o, &err);
    if (code == FC_OK)
        code = fc_options_parse(&table, argc - 1, argv + 1, &o, &help, &err);
    if (help) {
        printf("usage: fluidcast-mesh-bench [options]\n\n");
        fc_options_print_help(stdout, &table);
        return 0;
    }
    if (code == FC_OK && o.frame_path[0] && o.radius <= 0.0f)
        code = fc_error_set(&err, FC_ERR_USAGE, "--frame needs --radius");
    if (code == FC_OK)
        code = run(&o, &err);
    if (code != FC_OK) {
        fprintf(stderr, "fluidcast-mesh-bench: %s\n", err.message);
        return 1;
    }
    return 0;
}
