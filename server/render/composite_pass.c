/* composite_pass.c — Fresnel compositing of the fluid over the background. */
#include "composite_pass.h"

#include "gl_util.h"
#include "normal_pass.h"
#include "shader_program.h"
#include "shader_variants.h"

/* Uniform locations fixed by layout(location) in camera.frag.glsl, composite.frag.glsl and fluid_pixel.frag.glsl. */
enum {
    LOC_FOCAL = 0,
    LOC_VIEWPORT = 5,
    LOC_LIGHT_VIEW = 6,
    LOC_FLUID_COLOR = 7,
    LOC_ABSORPTION = 8,
    LOC_FRESNEL_F0 = 9,
    LOC_REFRACTION = 10,
    LOC_SPECULAR = 11,
    LOC_SHININESS = 13,
    LOC_FOAM = 14,
    LOC_USE_ENVIRONMENT_MAP = 15,
    LOC_FLOOR_PLANE = 16,
    LOC_DEPTH_PROJECTION = 17,
    LOC_FOAM_NOISE_RANGE = 18,
    LOC_DEPTH_TEXEL_UV = 54,
    LOC_THICKNESS_TEXEL_UV = 43,
    LOC_BACKGROUND_TEXTURE_SIZE = 44,
    LOC_THICKNESS_PER_PIXEL = 45,
    LOC_THICKNESS_SIZE = 46,
    LOC_COLORED = 47,
    LOC_CONTACT_SHADOW = 57,
    LOC_DEPTH_DIMMING = 58
};
/* Texture units fixed by layout(binding) in the composite shaders (surface_normal.frag.glsl also has 3). */
enum { UNIT_SURFACE_DEPTH = 0, UNIT_THICKNESS = 1, UNIT_BACKGROUND = 2, UNIT_ENVIRONMENT_MAP = 4 };
/* Foam starts where the local mean of |N| (composite.frag.glsl) exceeds this
 * many times settings.noise, which only 1% of a calm surface reaches (its
 * median is 0.10), and is complete at the second, about the median where the
 * foam state raised the amplitude: foam marks turbulence, not ripples. */
#define FOAM_START 0.22f
#define FOAM_FULL 0.45f

static const char *const shade_files[] = {"fullscreen.vert.glsl", "camera.frag.glsl", "environment.frag.glsl",
                                          "surface_normal.frag.glsl", "fluid_pixel.frag.glsl", "composite.frag.glsl"};

fc_code fc_composite_pass_create(const char *shader_dir, bool flat_constants, fc_composite_pass *pass,
                                 fc_error *err)
{
    *pass = (fc_composite_pass){
        .srgb_target = fc_render_target_init(GL_SRGB8_ALPHA8, true, false),
        .float_target = fc_render_target_init(GL_RGBA32F, true, false),
    };
    glCreateVertexArrays(1, &pass->empty_vertex_array);
    pass->depth_sampler = fc_gl_nearest_sampler();
    const char *mask[] = {"fullscreen.vert.glsl", "camera.frag.glsl", "fluid_pixel.frag.glsl",
                          "fluid_mask.frag.glsl"};
    fc_code code = fc_program_build(shader_dir, mask, sizeof mask / sizeof mask[0], &pass->mask_program, err);
    /* The default look's variant now; others on first use. */
    if (code == FC_OK)
        code = fc_program_variants_create(&pass->programs,
                                          &(fc_program_options){.shader_dir = shader_dir,
                                                                .flat_constants = flat_constants},
                                          shade_files,
                                          sizeof shade_files / sizeof shade_files[0],
                                          FC_FEATURE_FLOOR | FC_FEATURE_SHADOW, err);
    return code;
}

void fc_composite_pass_destroy(fc_composite_pass *pass)
{
    glDeleteProgram(pass->mask_program);
    fc_program_variants_destroy(&pass->programs);
    glDeleteVertexArrays(1, &pass->empty_vertex_array);
    glDeleteSamplers(1, &pass->depth_sampler);
    pass->depth_sampler = 0;
    fc_render_target_release(&pass->srgb_target);
    fc_render_target_release(&pass->float_target);
    pass->mask_program = pass->empty_vertex_array = 0;
}

/* Schlick's reflectance at normal incidence for a fluid of index `ior` in air. */
static float fresnel_f0(float ior)
{
    float r = (ior - 1.0f) / (ior + 1.0f);
    return r * r;
}

/* Absorption is given per particle radius of thickness (so a scene looks the
 * same in any unit) and applied per world unit; refraction is per pixel of
 * projected thickness (composite.frag.glsl), unit-free already. */
/* Whether the composite draws foam: it needs the noise. */
static bool has_foam(const fc_settings *settings)
{
    return settings->foam > 0.0f && settings->noise > 0.0f;
}

#define ACTIVE(location) fc_uniform_active(uniforms, location)

static void apply_material(const fc_settings *settings, bool colored, uint64_t uniforms)
{
    const float per_radius = 1.0f / settings->radius;
    float absorption[3] = {settings->absorption[0], settings->absorption[1], settings->absorption[2]};
    /* Coloured, the fluid's colour comes from the particles: the absorption
     * is made grey (the channels' mean), so that fluid of any thickness
     * shows the attribute's colour over the background, not its colour
     * shifted towards the water's channel that absorbs least. */
    if (colored)
        absorption[0] = absorption[1] = absorption[2] = (absorption[0] + absorption[1] + absorption[2]) / 3.0f;
    if (ACTIVE(LOC_COLORED))
        glUniform1i(LOC_COLORED, colored);
    if (ACTIVE(LOC_FLUID_COLOR))
        glUniform3fv(LOC_FLUID_COLOR, 1, settings->fluid_color);
    if (ACTIVE(LOC_ABSORPTION))
        glUniform3f(LOC_ABSORPTION, absorption[0] * per_radius, absorption[1] * per_radius,
                    absorption[2] * per_radius);
    if (ACTIVE(LOC_FRESNEL_F0))
        glUniform1f(LOC_FRESNEL_F0, fresnel_f0(settings->ior));
    if (ACTIVE(LOC_REFRACTION))
        glUniform1f(LOC_REFRACTION, settings->refraction);
    if (ACTIVE(LOC_SPECULAR))
        glUniform1f(LOC_SPECULAR, settings->specular);
    if (ACTIVE(LOC_SHININESS))
        glUniform1f(LOC_SHININESS, settings->shininess);
    if (ACTIVE(LOC_CONTACT_SHADOW))
        glUniform1f(LOC_CONTACT_SHADOW, settings->contact_shadow);
    if (ACTIVE(LOC_DEPTH_DIMMING))
        glUniform1f(LOC_DEPTH_DIMMING, settings->depth_dimming);
    /* No noise, no foam; the range must stay non-empty even then (smoothstep). */
    bool foam = has_foam(settings);
    float noise = foam ? settings->noise : 1.0f;
    if (ACTIVE(LOC_FOAM))
        glUniform1f(LOC_FOAM, foam ? settings->foam : 0.0f);
    if (ACTIVE(LOC_FOAM_NOISE_RANGE))
        glUniform2f(LOC_FOAM_NOISE_RANGE, FOAM_START * noise, FOAM_FULL * noise);
}

/* The thickness may have any resolution: the shader maps pixels to its texels. */
static void bind_thickness(const fc_render_target *thickness, const fc_view *view, uint64_t uniforms)
{
    glBindTextureUnit(UNIT_THICKNESS, thickness->color);
    if (ACTIVE(LOC_THICKNESS_TEXEL_UV))
        glUniform2f(LOC_THICKNESS_TEXEL_UV, 1.0f / (float)thickness->texture_width,
                    1.0f / (float)thickness->texture_height);
    if (ACTIVE(LOC_THICKNESS_PER_PIXEL))
        glUniform2f(LOC_THICKNESS_PER_PIXEL, (float)thickness->width / (float)view->width,
                    (float)thickness->height / (float)view->height);
    if (ACTIVE(LOC_THICKNESS_SIZE))
        glUniform2f(LOC_THICKNESS_SIZE, (float)thickness->width, (float)thickness->height);
}

static void bind_inputs(const fc_composite_inputs *in, const fc_view *view, float radius, uint64_t uniforms)
{
    fc_surface_normal_bind(in->surface_depth, in->noise, radius, uniforms);
    bind_thickness(in->thickness, view, uniforms);
    glBindTextureUnit(UNIT_BACKGROUND, in->background->color);
    if (ACTIVE(LOC_BACKGROUND_TEXTURE_SIZE))
        glUniform2f(LOC_BACKGROUND_TEXTURE_SIZE, (float)in->background->texture_width,
                    (float)in->background->texture_height);
    if (ACTIVE(LOC_USE_ENVIRONMENT_MAP))
        glUniform1i(LOC_USE_ENVIRONMENT_MAP, in->environment_map != 0);
    if (in->environment_map) {
        glBindTextureUnit(UNIT_ENVIRONMENT_MAP, in->environment_map);
        glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
    }
}

/* The uniforms of fluid_pixel.frag.glsl (and the camera's it uses) on `program`. */
static void apply_fluid_pixel(GLuint program, const fc_view *view, const fc_environment *env,
                              const fc_render_target *surface_depth)
{
    glProgramUniform2f(program, LOC_DEPTH_TEXEL_UV, 1.0f / (float)surface_depth->texture_width,
                       1.0f / (float)surface_depth->texture_height);
    glProgramUniform2f(program, LOC_FOCAL, view->fx, view->fy);
    glProgramUniform2f(program, LOC_VIEWPORT, (float)view->width, (float)view->height);
    glProgramUniform4fv(program, LOC_FLOOR_PLANE, 1, env->floor_plane);
}

/* Stencil 1 on the fluid pixels, 0 elsewhere, and the fluid's depth; no colour. */
static void draw_mask(const fc_composite_pass *pass, const fc_composite_inputs *in, const fc_render_target *target)
{
    const GLint clear = 0;
    glClearNamedFramebufferiv(target->framebuffer, GL_STENCIL, 0, &clear);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(in->depth_tested ? GL_LESS : GL_ALWAYS);
    glDepthMask(GL_TRUE);
    glEnable(GL_STENCIL_TEST);
    glStencilFunc(GL_ALWAYS, 1, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glUseProgram(pass->mask_program);
    glBindTextureUnit(UNIT_SURFACE_DEPTH, in->surface_depth->color);
    fc_gl_draw_fullscreen(pass->empty_vertex_array);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
}

/* The shading runs where the mask's stencil is 1, whichever pass laid it down. */
static void shade_on_mask(void)
{
    glEnable(GL_STENCIL_TEST);
    glDepthMask(GL_FALSE);
    glDisable(GL_DEPTH_TEST);
    glStencilFunc(GL_EQUAL, 1, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
}

/* The shader variant a render needs (shader_variants.h). A cube map replaces
 * the scene in reflections, the only place the composite shows it. */
static unsigned shade_features(const fc_composite_inputs *in, const fc_environment *env, const fc_settings *settings)
{
    unsigned features = in->environment_map ? FC_FEATURE_ENVIRONMENT_MAP : fc_environment_features(env);
    if (in->noise)
        features |= FC_FEATURE_NOISE;
    if (in->noise && has_foam(settings))
        features |= FC_FEATURE_FOAM;
    if (in->colored)
        features |= FC_FEATURE_COLORED;
    return features;
}

fc_code fc_composite_pass_target(fc_composite_pass *pass, const fc_view *view, bool want_u8,
                                 const fc_render_target **target, fc_error *err)
{
    fc_render_target *t = want_u8 ? &pass->srgb_target : &pass->float_target;
    *target = t;
    return fc_render_target_resize(t, view->width, view->height, err);
}

fc_code fc_composite_pass_run(fc_composite_pass *pass, const fc_composite_inputs *in, const fc_view *view,
                              const fc_environment *env, const fc_settings *settings, bool want_u8,
                              const fc_render_target **result, fc_error *err)
{
    const fc_program_variant *shade = NULL;
    fc_code code = fc_program_variants_get(&pass->programs, shade_features(in, env, settings), &shade, err);
    const fc_render_target *target = NULL;
    if (code == FC_OK)
        code = fc_composite_pass_target(pass, view, want_u8, &target, err);
    if (code != FC_OK)
        return code;
    fc_render_target_bind(target);
    glDisable(GL_BLEND);
    /* The shaders work in linear RGB; the sRGB target encodes on write. */
    if (want_u8)
        glEnable(GL_FRAMEBUFFER_SRGB);
    else
        glDisable(GL_FRAMEBUFFER_SRGB);
    /* The mask's and the shading's lookups of the fluid's depth (fluid_pixel.frag.glsl). */
    glBindSampler(UNIT_SURFACE_DEPTH, pass->depth_sampler);
    if (!in->masked) {
        apply_fluid_pixel(pass->mask_program, view, env, in->surface_depth);
        glProgramUniform2f(pass->mask_program, LOC_DEPTH_PROJECTION, view->p22, view->p32);   /* it writes the fluid's depth */
        draw_mask(pass, in, target);
    }
    shade_on_mask();
    glUseProgram(shade->program);
    uint64_t uniforms = shade->uniforms;
    fc_environment_apply_to(env, view, uniforms);
    if (ACTIVE(LOC_LIGHT_VIEW))
        glUniform3fv(LOC_LIGHT_VIEW, 1, env->light_view);
    if (ACTIVE(LOC_FLOOR_PLANE))
        glUniform4fv(LOC_FLOOR_PLANE, 1, env->floor_plane);
    apply_material(settings, in->colored, uniforms);
    bind_inputs(in, view, settings->radius, uniforms);
    if (ACTIVE(LOC_DEPTH_TEXEL_UV))
        glUniform2f(LOC_DEPTH_TEXEL_UV, 1.0f / (float)in->surface_depth->texture_width,
                    1.0f / (float)in->surface_depth->texture_height);
    fc_gl_draw_fullscreen(pass->empty_vertex_array);   /* the stencil keeps it to the fluid */
    glBindSampler(UNIT_SURFACE_DEPTH, 0);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glDepthMask(GL_TRUE);
    *result = target;
    return fc_gl_check("composite pass", err);
}
