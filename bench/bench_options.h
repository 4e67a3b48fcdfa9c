/* bench_options.h — the command line of fluidcast-bench. */
#ifndef FC_BENCH_OPTIONS_H
#define FC_BENCH_OPTIONS_H

#include "depth_pass.h"
#include "egl_context.h"
#include "fluidcast_types.h"
#include "pipeline.h"

#define BENCH_MAX_LIST 16
/* In the iterations list: the method's own default (fc_smoothing_default_iterations). */
#define BENCH_DEFAULT_ITERATIONS UINT32_MAX

typedef enum bench_action {
    BENCH_RUN = 0,           /* render every configuration and print the table */
    BENCH_WRITE_SCENE,       /* write the scene of the (single) particle count as .f32 and exit */
    BENCH_HELP
} bench_action;

typedef struct bench_options {
    bench_action action;
    const char *scene_path;  /* BENCH_WRITE_SCENE */
    const char *image_path;  /* PNG of every configuration's last frame, in turn; NULL: none */
    fc_gpu_choice gpu;
    uint64_t particles[BENCH_MAX_LIST];
    int n_particles;
    uint32_t sizes[BENCH_MAX_LIST][2];
    int n_sizes;
    fc_smoothing smoothings[BENCH_MAX_LIST];
    int n_smoothings;
    uint32_t iterations[BENCH_MAX_LIST];   /* or BENCH_DEFAULT_ITERATIONS */
    int n_iterations;
    float smooth_scales[BENCH_MAX_LIST];   /* --scale, fc_settings.smooth_scale: 1, 0.5, 0.25 */
    int n_smooth_scales;
    int frames;
    fc_image_format format;  /* 0 = no encoding */
    int profile;             /* --profile: a per-pass table after each row */
    const char *shader_dir;  /* --shader-dir: GLSL from there instead of the built-in copies; NULL: built-in */
    fc_splat_method splat;   /* --splat: the surface splat forced on the pipeline; AUTO: its own choice */
    uint32_t filter_radius;  /* --filter-radius: fc_settings.filter_radius; 0: from the projected particle size */
    fc_kernel kernel;        /* --kernel: fc_settings.kernel */
    bool shadow;             /* --shadow: fc_settings.shadow */
    float thickness_scale;   /* --thickness-scale: fc_settings.thickness_scale; 0: fluidcast's default */
    fc_constants_path constants;   /* --constants: fc_pipeline_config.constants */
} bench_options;

/* Defaults: 64k particles, 1280x720, curvature flow 40 iterations at full
 * resolution, 10 frames, PNG. */
void bench_options_default(bench_options *o);

/* Parses argv over the defaults; FC_ERR_USAGE with the offending argument. */
fc_code bench_options_parse(int argc, char **argv, bench_options *o, fc_error *err);

void bench_options_print_usage(void);

/* The --smoothing name of a method, "?" for one without a name. */
const char *bench_smoothing_name(fc_smoothing s);

#endif
