/* render_debug.c — renders a raw .f32 particle file to a binary PPM (colour)
 * or PGM (AOVs, depth range stretched to 0..255; PFM keeps the floats) so a
 * person can look at the pipeline's output; not a test. Convert with e.g.
 * `oiiotool out.ppm -o out.png`.
 *
 * usage: fc_render_debug in.f32 out.ppm|out.pgm|out.pfm width height radius
 *        eye_x eye_y eye_z target_x target_y target_z up_x up_y up_z fov_y
 *        [color|depth|smoothed|thickness] [iterations]
 * FC_SHADER_DIR, when set, loads the shaders from that directory instead of
 * the built-in copies, to try shader changes without rebuilding. */
#include <float.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "egl_context.h"
#include "fc_error.h"
#include "fc_frame.h"
#include "pipeline.h"

static int read_f32(const char *path, fc_frame *frame)
{
    FILE *f = fopen(path, "rb");
    if (!f || fseek(f, 0, SEEK_END) != 0)
        return 0;
    long bytes = ftell(f);
    rewind(f);
    fc_error err;
    int ok = bytes > 0 && fc_frame_alloc(frame, (uint64_t)bytes / 12, 0, &err) == FC_OK &&
             fread(frame->positions, 12, frame->count, f) == frame->count;
    fclose(f);
    return ok;
}

static fc_aov parse_aov(const char *name)
{
    if (strcmp(name, "depth") == 0)
        return FC_AOV_DEPTH;
    if (strcmp(name, "smoothed") == 0)
        return FC_AOV_SMOOTHED_DEPTH;
    if (strcmp(name, "thickness") == 0)
        return FC_AOV_THICKNESS;
    return FC_AOV_COLOR;
}

static void write_ppm(FILE *out, const fc_image *img)
{
    fprintf(out, "P6\n%u %u\n255\n", img->width, img->height);
    const unsigned char *rgba = img->pixels;
    for (size_t i = 0; i < (size_t)img->width * img->height; i++)
        fwrite(rgba + 4 * i, 1, 3, out);
}

/* Little-endian greyscale PFM: the float values as they are, rows bottom to top. */
static void write_pfm(FILE *out, const fc_image *img)
{
    fprintf(out, "Pf\n%u %u\n-1.0\n", img->width, img->height);
    const float *v = img->pixels;
    for (uint32_t row = img->height; row-- > 0;)
        fwrite(v + (size_t)row * img->width, sizeof(float), img->width, out);
}

/* Stretches the non-zero values over 1..255 so small depth differences show; 0 stays black. */
static void write_pgm(FILE *out, const fc_image *img)
{
    const float *v = img->pixels;
    size_t n = (size_t)img->width * img->height;
    float lo = FLT_MAX, hi = 0.0f;
    for (size_t i = 0; i < n; i++)
        if (v[i] > 0.0f) {
            lo = v[i] < lo ? v[i] : lo;
            hi = v[i] > hi ? v[i] : hi;
        }
    fprintf(out, "P5\n%u %u\n255\n", img->width, img->height);
    for (size_t i = 0; i < n; i++) {
        unsigned char g = v[i] > 0.0f ? (unsigned char)(1.0f + 254.0f * (hi - v[i]) / (hi - lo + 1e-30f)) : 0;
        fputc(g, out);
    }
}

int main(int argc, char **argv)
{
    if (argc < 16) {
        fprintf(stderr, "usage: %s in.f32 out width height radius eye(3) target(3) up(3) fov_y "
                        "[color|depth|smoothed|thickness] [iterations]\n", argv[0]);
        return 2;
    }
    fc_camera cam = {.width = (uint32_t)atoi(argv[3]), .height = (uint32_t)atoi(argv[4])};
    for (int i = 0; i < 3; i++) {
        cam.eye[i] = strtof(argv[6 + i], NULL);
        cam.target[i] = strtof(argv[9 + i], NULL);
        cam.up[i] = strtof(argv[12 + i], NULL);
    }
    cam.fov_y_deg = strtof(argv[15], NULL);
    fc_settings settings;
    fc_settings_default(&settings);
    settings.radius = strtof(argv[5], NULL);
    fc_aov aov = argc > 16 ? parse_aov(argv[16]) : FC_AOV_COLOR;
    if (argc > 17)
        settings.iterations = (uint32_t)atoi(argv[17]);

    fc_frame frame = {0};
    if (!read_f32(argv[1], &frame)) {
        fprintf(stderr, "cannot read %s\n", argv[1]);
        return 1;
    }
    fc_gpu_choice gpu = {FC_GPU_AUTO, 0};
    fc_gl_context *gl = NULL;
    fc_pipeline *pipeline = NULL;
    fc_image img = {0};
    fc_error err = {0};
    float upload_ms = -1.0f, stage_ms[FC_STAGE_COUNT];
    fc_code code = fc_gl_context_create(&gpu, &gl, &err);
    if (code == FC_OK)
        code = fc_pipeline_create(&(fc_pipeline_config){getenv("FC_SHADER_DIR")}, &pipeline, &err);
    if (code == FC_OK)
        code = fc_pipeline_upload(pipeline, &frame, &upload_ms, &err);
    if (code == FC_OK)
        code = fc_pipeline_render(pipeline, &cam, &settings, aov, 1, &img, stage_ms, &err);
    FILE *out = code == FC_OK ? fopen(argv[2], "wb") : NULL;
    if (out) {
        const char *extension = strrchr(argv[2], '.');
        if (aov == FC_AOV_COLOR)
            write_ppm(out, &img);
        else if (extension && strcmp(extension, ".pfm") == 0)
            write_pfm(out, &img);
        else
            write_pgm(out, &img);
        fclose(out);
        printf("%s: %llu particles, upload %.2f ms, depth %.2f, thickness %.2f, smoothing %.2f, "
               "composite %.2f, readback %.2f ms\n", fc_gl_context_renderer(gl), (unsigned long long)frame.count,
               upload_ms, stage_ms[FC_STAGE_DEPTH], stage_ms[FC_STAGE_THICKNESS], stage_ms[FC_STAGE_SMOOTHING],
               stage_ms[FC_STAGE_COMPOSITE], stage_ms[FC_STAGE_READBACK]);
    } else {
        fprintf(stderr, "%s\n", code == FC_OK ? "cannot write the output" : err.message);
    }
    fc_image_free(&img);
    fc_pipeline_destroy(pipeline);
    fc_gl_context_destroy(gl);
    fc_frame_free(&frame);
    return out ? 0 : 1;
}
