/* fc_settings.c — default render settings and their domains. */
#include "fc_frame.h"

#include <math.h>

#include "fc_error.h"

#define MAX_RADIUS 1e6f
#define MAX_ITERATIONS 1000u
#define MAX_FILTER_RADIUS 64u
#define MAX_ABSORPTION 1e6f
#define MIN_IOR 1.0f
#define MAX_IOR 3.0f
#define MAX_REFRACTION 1000.0f
#define MAX_SPECULAR 10.0f
#define MIN_SHININESS 1.0f
#define MAX_SHININESS 10000.0f
#define MAX_THICKNESS_BLUR 32u
#define MAX_NOISE 10.0f
#define MAX_FOAM 10.0f
#define MAX_EXPOSURE 16.0f

uint32_t fc_smoothing_default_iterations(fc_smoothing method)
{
    /* Chosen by eye on the sample scenes at 640x480 (docs/gallery): enough to
     * hide the individual spheres without melting detail. */
    switch (method) {
    case FC_SMOOTHING_CURVATURE: return 60;
    case FC_SMOOTHING_BILATERAL: return 2;
    case FC_SMOOTHING_BINOMIAL: return 8;
    case FC_SMOOTHING_NARROW: return 4;
    case FC_SMOOTHING_NONE: break;
    }
    return 0;
}

void fc_settings_default(fc_settings *s)
{
    *s = (fc_settings){
        .radius = 0.0f,
        .smoothing = FC_SMOOTHING_NARROW,
        .iterations = fc_smoothing_default_iterations(FC_SMOOTHING_NARROW),
        .filter_radius = 0,
        .smooth_scale = 1.0f,
        .fluid_color = {0.02f, 0.15f, 0.28f},
        .absorption = {0.2f, 0.07f, 0.035f},
        .ior = 1.33f,
        .refraction = 0.25f,
        .specular = 0.6f,
        .shininess = 60.0f,
        .thickness_scale = 0.5f,
        .thickness_blur = 2,
        .noise = 0.0f,
        .foam = 0.0f,
        .foam_tau = 0.5f,
        .foam_decay = 0.85f,
        .density_threshold = 0.0f,
        .kernel = FC_KERNEL_SPHERE,
        .shadow = 1,
        .exposure = 0.0f,
        .color_by = FC_COLOR_BY_NONE,
        .colormap = FC_COLORMAP_VIRIDIS,
        .color_range = {0.0f, 1.0f},
        .jpeg_subsampling = FC_JPEG_SUBSAMPLING_YUV444,
    };
}

/* NaN fails both comparisons, so this also rejects non-finite values. */
static bool in_range(float v, float lo, float hi)
{
    return v >= lo && v <= hi;
}

/* The passes render at full, half or quarter resolution, nothing in between. */
static bool is_resolution_scale(float v)
{
    return v == 1.0f || v == 0.5f || v == 0.25f;
}

static bool is_known_smoothing(fc_smoothing smoothing)
{
    return (unsigned)smoothing <= FC_SMOOTHING_NARROW;
}

static fc_code out_of_range(fc_error *err, const char *name, float v, float lo, float hi)
{
    return fc_error_set(err, FC_ERR_INVALID_VALUE, "%s %g is outside [%g, %g]", name, (double)v, (double)lo,
                        (double)hi);
}

static fc_code validate_shape(const fc_settings *s, fc_error *err)
{
    if ((unsigned)s->kernel > FC_KERNEL_ANISOTROPIC)
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "unknown kernel %u", (unsigned)s->kernel);
    if (!in_range(s->radius, 0.0f, MAX_RADIUS))
        return out_of_range(err, "radius", s->radius, 0.0f, MAX_RADIUS);
    if (!is_known_smoothing(s->smoothing))
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "unknown smoothing %u", (unsigned)s->smoothing);
    if (s->iterations > MAX_ITERATIONS)
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "iterations %u exceed %u", s->iterations, MAX_ITERATIONS);
    if (s->filter_radius > MAX_FILTER_RADIUS)
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "filter_radius %u exceeds %u pixels", s->filter_radius,
                            MAX_FILTER_RADIUS);
    if (!is_resolution_scale(s->smooth_scale))
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "smooth_scale %g is not 1, 0.5 or 0.25",
                            (double)s->smooth_scale);
    if (!is_resolution_scale(s->thickness_scale))
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "thickness_scale %g is not 1, 0.5 or 0.25",
                            (double)s->thickness_scale);
    if (s->thickness_blur > MAX_THICKNESS_BLUR)
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "thickness_blur %u exceeds %u pixels", s->thickness_blur,
                            MAX_THICKNESS_BLUR);
    return FC_OK;
}

static fc_code validate_shading(const fc_settings *s, fc_error *err)
{
    for (int c = 0; c < 3; c++) {
        if (!in_range(s->fluid_color[c], 0.0f, 1.0f))
            return fc_error_set(err, FC_ERR_INVALID_VALUE, "fluid_color[%d] %g is outside [0, 1]", c,
                                (double)s->fluid_color[c]);
        if (!in_range(s->absorption[c], 0.0f, MAX_ABSORPTION))
            return fc_error_set(err, FC_ERR_INVALID_VALUE, "absorption[%d] %g is outside [0, %g]", c,
                                (double)s->absorption[c], (double)MAX_ABSORPTION);
    }
    if (!in_range(s->ior, MIN_IOR, MAX_IOR))
        return out_of_range(err, "ior", s->ior, MIN_IOR, MAX_IOR);
    if (!in_range(s->refraction, 0.0f, MAX_REFRACTION))
        return out_of_range(err, "refraction", s->refraction, 0.0f, MAX_REFRACTION);
    if (!in_range(s->specular, 0.0f, MAX_SPECULAR))
        return out_of_range(err, "specular", s->specular, 0.0f, MAX_SPECULAR);
    if (!in_range(s->shininess, MIN_SHININESS, MAX_SHININESS))
        return out_of_range(err, "shininess", s->shininess, MIN_SHININESS, MAX_SHININESS);
    if (s->shadow > 1)
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "shadow %u is not 0 (off) or 1 (on)", s->shadow);
    if (!in_range(s->exposure, -MAX_EXPOSURE, MAX_EXPOSURE))
        return out_of_range(err, "exposure", s->exposure, -MAX_EXPOSURE, MAX_EXPOSURE);
    return FC_OK;
}

static fc_code validate_effects(const fc_settings *s, fc_error *err)
{
    if (!in_range(s->noise, 0.0f, MAX_NOISE))
        return out_of_range(err, "noise", s->noise, 0.0f, MAX_NOISE);
    if (!in_range(s->foam, 0.0f, MAX_FOAM))
        return out_of_range(err, "foam", s->foam, 0.0f, MAX_FOAM);
    if (!(s->foam_tau > 0.0f && isfinite(s->foam_tau)))
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "foam_tau %g must be finite and > 0", (double)s->foam_tau);
    /* A decay of 1 would never let a raised amplitude fall back. */
    if (!(s->foam_decay >= 0.0f && s->foam_decay < 1.0f))
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "foam_decay %g is outside [0, 1)", (double)s->foam_decay);
    if (!(s->density_threshold >= 0.0f && isfinite(s->density_threshold)))
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "density_threshold %g must be finite and >= 0",
                            (double)s->density_threshold);
    return FC_OK;
}

/* The range must map to the colormap with a finite, positive width (its
 * width is a divisor in the shader) when it is used; without colouring it
 * need only be finite, so zeroed settings stay valid. */
static fc_code validate_coloring(const fc_settings *s, fc_error *err)
{
    if ((unsigned)s->color_by > FC_COLOR_BY_DENSITY)
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "unknown color_by %u", (unsigned)s->color_by);
    if ((unsigned)s->colormap > FC_COLORMAP_TURBO)
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "unknown colormap %u", (unsigned)s->colormap);
    float lo = s->color_range[0], hi = s->color_range[1];
    if (!(isfinite(lo) && isfinite(hi) && isfinite(hi - lo)))
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "color_range [%g, %g] must be finite", (double)lo,
                            (double)hi);
    if (s->color_by != FC_COLOR_BY_NONE && !(lo < hi))
        return fc_error_set(err, FC_ERR_INVALID_VALUE,
                            "color_range [%g, %g]: min must be below max to colour by an attribute", (double)lo,
                            (double)hi);
    return FC_OK;
}

fc_code fc_settings_validate(const fc_settings *s, fc_error *err)
{
    fc_code code = validate_shape(s, err);
    if (code == FC_OK)
        code = validate_shading(s, err);
    if (code == FC_OK)
        code = validate_effects(s, err);
    if (code == FC_OK)
        code = validate_coloring(s, err);
    if (code == FC_OK && (unsigned)s->jpeg_subsampling > FC_JPEG_SUBSAMPLING_YUV420)
        code = fc_error_set(err, FC_ERR_INVALID_VALUE, "unknown jpeg_subsampling %u",
                            (unsigned)s->jpeg_subsampling);
    return code;
}
