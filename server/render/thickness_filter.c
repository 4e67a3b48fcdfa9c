/* thickness_filter.c — Gaussian blur and resampling of the thickness. */
#include "thickness_filter.h"

#include <math.h>
#include <stdlib.h>

#include "gl_util.h"
#include "shader_program.h"

/* Uniform locations fixed by layout(location) in thickness_taps.frag.glsl. */
enum {
    LOC_AXIS = 0,
    LOC_TAP_COUNT = 1,
    LOC_SOURCE_PER_TARGET = 2,
    LOC_SOURCE_SIZE = 3,
    LOC_SOURCE_TEXEL_UV = 4,
    LOC_TAPS = 8
};
/* The length of taps[] in thickness_taps.frag.glsl (max_taps). */
#define MAX_TAPS 64
/* The kernel is cut at this many standard deviations, where weights are about 1%. */
#define KERNEL_SIGMAS 3.0f
/* Bounds the kernel whatever blur a client asks for: 2r + 1 taps must fit. */
#define MAX_RADIUS ((MAX_TAPS - 1) / 2)

/* One bilinear lookup of the shader: an element of its taps[]. */
typedef struct blur_tap {
    float offset;   /* along the axis, source texels */
    float weight;
} blur_tap;

/* A filter whose targets have `format` and whose blur sums the channels
 * `blur_file` reads. */
static fc_code create(const char *shader_dir, GLenum format, const char *blur_file, fc_thickness_filter *f,
                      fc_error *err)
{
    *f = (fc_thickness_filter){
        .across = fc_render_target_init(format, false, true),
        .result = fc_render_target_init(format, false, true),
        .upsampled = fc_render_target_init(format, false, true),
    };
    glCreateVertexArrays(1, &f->empty_vertex_array);
    const char *files[] = {"fullscreen.vert.glsl", "thickness_taps.frag.glsl", blur_file};
    return fc_program_build(shader_dir, files, sizeof files / sizeof files[0], &f->program, err);
}

fc_code fc_thickness_filter_create(const char *shader_dir, fc_thickness_filter *f, fc_error *err)
{
    return create(shader_dir, GL_R32F, "thickness_blur.frag.glsl", f, err);
}

fc_code fc_thickness_filter_create_color(const char *shader_dir, fc_thickness_filter *f, fc_error *err)
{
    return create(shader_dir, GL_RGBA32F, "thickness_color_blur.frag.glsl", f, err);
}

void fc_thickness_filter_destroy(fc_thickness_filter *f)
{
    glDeleteProgram(f->program);
    glDeleteVertexArrays(1, &f->empty_vertex_array);
    fc_render_target_release(&f->across);
    fc_render_target_release(&f->result);
    fc_render_target_release(&f->upsampled);
    f->program = f->empty_vertex_array = 0;
}

/* Unnormalised Gaussian weights of the offsets 0..r into w, sigma > 0; returns r. */
static int gaussian(float sigma, float w[MAX_RADIUS + 1])
{
    /* The small margin keeps a sigma of exactly n/3 from rounding up to n + 1 taps. */
    int r = (int)ceilf(KERNEL_SIGMAS * sigma - 1e-3f);
    r = r < MAX_RADIUS ? r : MAX_RADIUS;
    w[0] = 1.0f;
    for (int i = 1; i <= r; i++)
        w[i] = expf(-0.5f * (float)(i * i) / (sigma * sigma));
    return r;
}

/* One tap per weight, `spacing` source texels (one target pixel) apart:
 * where the pass also resamples, each tap already spans several texels. */
static int spaced_taps(float sigma, float spacing, blur_tap taps[MAX_TAPS])
{
    float w[MAX_RADIUS + 1];
    int r = gaussian(sigma, w);
    int n = 0;
    for (int i = -r; i <= r; i++)
        taps[n++] = (blur_tap){(float)i * spacing, w[abs(i)]};
    return n;
}

/* Source and target texels coincide: the centre alone, then the weights of
 * offsets i and i + 1 (i = 1, 3, ...) on each side as one tap at their
 * weighted mean offset, where bilinear filtering weighs the two texels so. */
static int merged_taps(float sigma, blur_tap taps[MAX_TAPS])
{
    float w[MAX_RADIUS + 2];
    int r = gaussian(sigma, w);
    w[r + 1] = 0.0f;
    int n = 0;
    taps[n++] = (blur_tap){0.0f, w[0]};
    for (int i = 1; i <= r; i += 2) {
        float pair = w[i] + w[i + 1];
        float offset = ((float)i * w[i] + (float)(i + 1) * w[i + 1]) / pair;
        taps[n++] = (blur_tap){offset, pair};
        taps[n++] = (blur_tap){-offset, pair};
    }
    return n;
}

static void normalise(blur_tap *taps, int n)
{
    float total = 0.0f;
    for (int i = 0; i < n; i++)
        total += taps[i].weight;
    for (int i = 0; i < n; i++)
        taps[i].weight /= total;
}

/* One pass from `source` into `target` at width x height, summing `taps`
 * along `axis` (0 is x, 1 is y). */
static fc_code draw_taps(fc_thickness_filter *f, const fc_render_target *source, fc_render_target *target, int axis,
                         blur_tap *taps, int n, uint32_t width, uint32_t height, fc_error *err)
{
    fc_code code = fc_render_target_resize(target, width, height, err);
    if (code != FC_OK)
        return code;
    normalise(taps, n);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_FRAMEBUFFER_SRGB);
    fc_render_target_bind(target);
    glUseProgram(f->program);
    glUniform2f(LOC_AXIS, axis == 0 ? 1.0f : 0.0f, axis == 1 ? 1.0f : 0.0f);
    glUniform1i(LOC_TAP_COUNT, n);
    glUniform2f(LOC_SOURCE_PER_TARGET, (float)source->width / (float)width, (float)source->height / (float)height);
    glUniform2f(LOC_SOURCE_SIZE, (float)source->width, (float)source->height);
    glUniform2f(LOC_SOURCE_TEXEL_UV, 1.0f / (float)source->texture_width, 1.0f / (float)source->texture_height);
    glUniform2fv(LOC_TAPS, n, &taps[0].offset);
    glBindTextureUnit(0, source->color);
    fc_gl_draw_fullscreen(f->empty_vertex_array);
    return fc_gl_check("thickness blur", err);
}

/* A single bilinear tap per pixel. */
static fc_code resample(fc_thickness_filter *f, const fc_render_target *source, fc_render_target *target,
                        uint32_t width, uint32_t height, fc_error *err)
{
    blur_tap tap = {0.0f, 1.0f};
    return draw_taps(f, source, target, 0, &tap, 1, width, height, err);
}

fc_code fc_thickness_filter_run(fc_thickness_filter *f, const fc_render_target *source, float sigma,
                                uint32_t width, uint32_t height, const fc_render_target **result, fc_error *err)
{
    bool same_size = source->width == width && source->height == height;
    *result = same_size && sigma <= 0.0f ? source : &f->result;
    if (sigma <= 0.0f)
        return same_size ? FC_OK : resample(f, source, &f->result, width, height, err);
    blur_tap taps[MAX_TAPS];
    int n = source->width == width ? merged_taps(sigma, taps)
                                   : spaced_taps(sigma, (float)source->width / (float)width, taps);
    fc_code code = draw_taps(f, source, &f->across, 0, taps, n, width, height, err);
    if (code != FC_OK)
        return code;
    n = merged_taps(sigma, taps);
    return draw_taps(f, &f->across, &f->result, 1, taps, n, width, height, err);
}

fc_code fc_thickness_filter_upsample(fc_thickness_filter *f, const fc_render_target *source, uint32_t width,
                                     uint32_t height, const fc_render_target **result, fc_error *err)
{
    *result = &f->upsampled;
    return resample(f, source, &f->upsampled, width, height, err);
}
