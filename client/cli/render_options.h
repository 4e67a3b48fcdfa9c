/* render_options.h — the command line of `fluidcast render`: its own options
 * (range, frame rate, orbit, resume, video quality) and snapshot's camera,
 * image and render-setting options (snapshot_options.h), shared. */
#ifndef FC_RENDER_OPTIONS_H
#define FC_RENDER_OPTIONS_H

#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>

#include "render_inputs.h"
#include "snapshot_options.h"

#define FC_RENDER_DEFAULT_FPS 24u

typedef struct fc_render_options {
    bool help;
    fc_snapshot_options view;      /* -o, camera, size, settings...; view.input unused */
    const char **inputs;           /* INPUTS as given (malloc'd array of argv pointers) */
    uint32_t input_count;
    fc_frame_range range;          /* --start/--end/--step */
    bool video;                    /* -o names a .mp4/.webm; else an image pattern */
    uint32_t fps;
    bool has_orbit;
    float orbit_deg;               /* turn of the eye about the target over the sequence */
    const char *camera_path;       /* --camera-path FILE.json (camera_path.h), or NULL */
    bool skip_existing;
    bool has_quality;
    uint32_t quality;              /* video: constant-rate factor; .jpg: JPEG quality */
} fc_render_options;

/* Parses the arguments after "render". FC_ERR_USAGE for an unknown option or
 * bad value, no input, an output that is neither a video nor an image pattern
 * with one %d, --skip-existing or --aov with a video, --quality out of the
 * output's range, --camera-path with --eye/--target or --orbit, or what
 * snapshot refuses. Free with fc_render_options_free. */
fc_code fc_render_parse(int argc, char **argv, fc_render_options *out, fc_error *err);
void fc_render_options_free(fc_render_options *o);
void fc_render_print_help(FILE *to);

#endif
