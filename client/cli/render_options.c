/* render_options.c — see render_options.h. */
#include "render_options.h"

#include <stdlib.h>
#include <string.h>

#include "cli_args.h"
#include "cli_read_options.h"
#include "cli_report.h"
#include "cli_values.h"
#include "fc_error.h"
#include "output_file.h"
#include "video_encoder.h"

static fc_code set_start(void *o, const char *name, const char *value, fc_error *err)
{
    fc_render_options *r = o;
    r->range.has_start = true;
    return fc_cli_parse_uint(name, value, 0, UINT32_MAX, &r->range.start, err);
}

static fc_code set_end(void *o, const char *name, const char *value, fc_error *err)
{
    fc_render_options *r = o;
    r->range.has_end = true;
    return fc_cli_parse_uint(name, value, 0, UINT32_MAX, &r->range.end, err);
}

static fc_code set_step(void *o, const char *name, const char *value, fc_error *err)
{
    return fc_cli_parse_uint(name, value, 1, UINT32_MAX, &((fc_render_options *)o)->range.step, err);
}

static fc_code set_fps(void *o, const char *name, const char *value, fc_error *err)
{
    return fc_cli_parse_uint(name, value, 1, 1000, &((fc_render_options *)o)->fps, err);
}

static fc_code set_orbit(void *o, const char *name, const char *value, fc_error *err)
{
    fc_render_options *r = o;
    r->has_orbit = true;
    return fc_cli_parse_float(name, value, &r->orbit_deg, err);
}

static fc_code set_camera_path(void *o, const char *name, const char *value, fc_error *err)
{
    if (value[0] == '\0')
        return fc_error_set(err, FC_ERR_USAGE, "%s needs a file name", name);
    ((fc_render_options *)o)->camera_path = value;
    return FC_OK;
}

static fc_code set_skip_existing(void *o, const char *name, const char *value, fc_error *err)
{
    (void)name, (void)value, (void)err;
    ((fc_render_options *)o)->skip_existing = true;
    return FC_OK;
}

/* Its range depends on the output: checked once the command line is complete. */
static fc_code set_quality(void *o, const char *name, const char *value, fc_error *err)
{
    fc_render_options *r = o;
    r->has_quality = true;
    return fc_cli_parse_uint(name, value, 0, 1000, &r->quality, err);
}

/* render's own options; the rest are snapshot's. */
static const fc_option own_options[] = {
    {"--start", "N", set_start, NULL, NULL},          {"--end", "N", set_end, NULL, NULL},
    {"--step", "N", set_step, NULL, NULL},            {"--fps", "F", set_fps, NULL, NULL},
    {"--orbit", "DEGREES", set_orbit, NULL, NULL},    {"--skip-existing", NULL, set_skip_existing, NULL, NULL},
    {"--quality", "Q", set_quality, NULL, NULL},      {"--camera-path", "PATH", set_camera_path, NULL, NULL},
};

static const fc_option_table own_table = {"fluidcast render", own_options,
                                          sizeof own_options / sizeof own_options[0], NULL, NULL};

static fc_code add_input(fc_render_options *o, const char *arg, fc_error *err)
{
    const char **grown = realloc(o->inputs, (o->input_count + 1) * sizeof *grown);
    if (!grown)
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for the input list");
    o->inputs = grown;
    o->inputs[o->input_count++] = arg;
    return FC_OK;
}

static fc_code take_argument(fc_render_options *o, int argc, char **argv, int *i, fc_error *err)
{
    const char *arg = argv[*i];
    if (arg[0] != '-' || arg[1] == '\0')
        return add_input(o, arg, err);
    bool known;
    fc_code code = fc_options_take(&own_table, argc, argv, i, o, &known, err);
    if (known)
        return code;
    code = fc_snapshot_take_option(&o->view, argc, argv, i, &known, err);
    if (!known)
        return fc_error_set(err, FC_ERR_USAGE, "unknown option %s (see fluidcast render --help)", arg);
    return code;
}

static fc_code check_video(fc_render_options *o, fc_error *err)
{
    const char *out = o->view.output;
    if (o->skip_existing)
        return fc_error_set(err, FC_ERR_USAGE, "--skip-existing resumes image sequences; %s is one video", out);
    if (o->view.aov != FC_AOV_COLOR)
        return fc_error_set(err, FC_ERR_USAGE, "--aov writes float channels: use an .exr pattern, not a video");
    if (o->view.width % 2 || o->view.height % 2)
        return fc_error_set(err, FC_ERR_USAGE, "video needs an even width and height (yuv420p), not --size %ux%u",
                            (unsigned)o->view.width, (unsigned)o->view.height);
    uint32_t max = fc_video_max_quality(out);
    if (!o->has_quality)
        o->quality = fc_video_default_quality(out);
    else if (o->quality > max)
        return fc_error_set(err, FC_ERR_USAGE, "--quality is the video's constant-rate factor, 0..%u for %s",
                            (unsigned)max, out);
    o->view.format = FC_FORMAT_RAW;
    return FC_OK;
}

static fc_code check_image_pattern(fc_render_options *o, fc_error *err)
{
    const char *out = o->view.output;
    if (!fc_is_frame_pattern(out))
        return fc_error_set(err, FC_ERR_USAGE,
                            "-o %s: give a video (.mp4, .webm) or an image pattern with one %%d, such as "
                            "frames/f_%%04d.png",
                            out);
    fc_code code = fc_output_format_from_path(out, &o->view.format, err);
    if (code != FC_OK)
        return code;
    if (o->view.aov != FC_AOV_COLOR && o->view.format != FC_FORMAT_EXR)
        return fc_error_set(err, FC_ERR_USAGE, "--aov writes float channels: the output must be .exr");
    if (o->has_quality && o->view.format != FC_FORMAT_JPEG)
        return fc_error_set(err, FC_ERR_USAGE, "--quality applies to videos and .jpg/.jpeg images only");
    if (o->has_quality && (o->quality < 1 || o->quality > 100))
        return fc_error_set(err, FC_ERR_USAGE, "--quality of JPEG images is 1..100");
    if (o->has_quality)
        o->view.quality = o->quality;
    return FC_OK;
}

static fc_code check_combinations(fc_render_options *o, fc_error *err)
{
    if (o->input_count == 0)
        return fc_error_set(err, FC_ERR_USAGE, "render needs particle files: a list, a glob, a %%04d or a {} pattern");
    if (!o->view.output)
        return fc_error_set(err, FC_ERR_USAGE, "render needs an output: -o OUT.mp4|.webm or -o frames/f_%%04d.png");
    if (o->camera_path && (o->view.has_eye || o->view.has_target))
        return fc_error_set(err, FC_ERR_USAGE, "--camera-path gives the camera: leave out --eye and --target");
    if (o->camera_path && o->has_orbit)
        return fc_error_set(err, FC_ERR_USAGE, "--camera-path gives the camera: leave out --orbit");
    o->video = fc_video_is_video_path(o->view.output);
    fc_code code = o->video ? check_video(o, err) : check_image_pattern(o, err);
    return code != FC_OK ? code : fc_snapshot_check_camera(&o->view, err);
}

fc_code fc_render_parse(int argc, char **argv, fc_render_options *out, fc_error *err)
{
    memset(out, 0, sizeof *out);
    fc_snapshot_set_defaults(&out->view);
    out->range.step = 1;
    out->fps = FC_RENDER_DEFAULT_FPS;
    for (int i = 0; i < argc; i++) {
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            out->help = true;
            return FC_OK;
        }
        fc_code code = take_argument(out, argc, argv, &i, err);
        if (code != FC_OK)
            return code;
    }
    return check_combinations(out, err);
}

void fc_render_options_free(fc_render_options *o)
{
    free(o->inputs);
    o->inputs = NULL;
    o->input_count = 0;
}

static void print_sequence_help(FILE *to)
{
    fprintf(to,
            "usage: fluidcast render INPUTS... -o OUT [options]\n"
            "\n"
            "Renders a sequence of particle files (the formats snapshot reads) on a\n"
            "fluidcastd server, in order, into a video or numbered images. The camera\n"
            "stays put over the sequence (unless --orbit or --camera-path moves it): it\n"
            "frames the fluid of all its frames, the union of their bounding boxes\n"
            "without droplets flung far from the rest, as snapshot frames one (a first\n"
            "pass reads every file for it), up guessed from the first frame.\n"
            "\n"
            "INPUTS: files in the order given; quoted globs ('out/*.ply', expanded here,\n"
            "numbers in names sorted by value); one pattern with a %%d (frame_%%04d.ply):\n"
            "frames from the lowest number that exists up to the first that is missing;\n"
            "or one pattern with {} standing for digits, padded or not\n"
            "('output/partio/ParticleData_Fluid_{}.bgeo'): every file that matches, by\n"
            "number (2 before 10).\n"
            "\n"
            "sequence:\n"
            "  -o, --output OUT        video (.mp4: H.264 with libx264, else MPEG-4;\n"
            "                          .webm: VP9; yuv420p, even sizes) or an image\n"
            "                          pattern with one %%d: frames/f_%%04d.png|.jpg|.exr,\n"
            "                          numbered like the input pattern's frames, else\n"
            "                          0, 1, 2... in order (a missing directory is made)\n"
            "  --start N, --end N      first and last frame number of a %%d or {} pattern\n"
            "                          (with --end every frame of a %%d one must exist)\n"
            "  --step N                every Nth frame of a pattern (default 1)\n"
            "  --fps N                 video frame rate, 1..1000 (default %u)\n"
            "  --quality Q             video: constant-rate factor, lower is better\n"
            "                          (H.264 0..51, default 23; VP9 0..63, default 32);\n"
            "                          .jpg: JPEG quality 1..100 (default 90)\n"
            "  --orbit DEGREES         turn the eye about the target around the up axis,\n"
            "                          DEGREES x i / N at frame i of N (360: a seamless loop)\n"
            "  --camera-path FILE.json camera keyframes, interpolated over the sequence:\n"
            "                          [{\"frame\": N, \"eye\": [x,y,z], \"target\": [x,y,z],\n"
            "                          \"up\": [x,y,z], \"fov\": DEG}, ...] (up and fov optional;\n"
            "                          frame: the number in the file names, else 0, 1...;\n"
            "                          eye and target on a Catmull-Rom spline through the\n"
            "                          keyframes, up and fov linear; held before the first\n"
            "                          and after the last)\n"
            "  --skip-existing         image patterns: leave frames whose image exists, to\n"
            "                          resume an interrupted batch (the camera is the same)\n"
            "\n"
            "camera and image (as for snapshot):\n"
            "  --server HOST:PORT      server address (default " FC_DEFAULT_SERVER ")\n"
            "                          or srv:NAME: one daemon of a DNS SRV name\n"
            "  --size WxH              image size (default 1280x720)\n"
            "  --eye X,Y,Z, --target X,Y,Z\n"
            "                          fixed look-at camera (both or neither)\n"
            "  --up X,Y,Z|x|y|z|-x|-y|-z\n"
            "                          up in the picture and axis of --orbit (default:\n"
            "                          guessed from the first frame's particles, printed)\n"
            "  --fov DEG               vertical field of view (default 40)\n"
            "  --aov NAME              an output variable instead of the colour (.exr only)\n"
            "\n",
            FC_RENDER_DEFAULT_FPS);
}

void fc_render_print_help(FILE *to)
{
    print_sequence_help(to);
    fc_cli_print_read_options_help(to, true);
    fc_snapshot_print_settings_help(to);
    fputs("On a terminal a progress bar shows frames, fps and the time left; otherwise one\n"
          "line per frame. A frame that cannot be read stops the render with its name; a\n"
          "video is finished so that the frames before it play. Ctrl-C (or SIGTERM)\n"
          "finishes the frame in flight and the video, and exits with 130 (143).\n"
          "  -h, --help              show this help\n"
          "\n",
          to);
    fc_cli_print_exit_codes(to);
}
