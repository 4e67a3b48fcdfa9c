/* composite_pass.c — Fresnel compositing of the fluid over the background. */
#include "composite_pass.h"

#include "gl_util.h"
#include "shader_program.h"

/* Uniform locations fixed by layout(location) in composite.frag.glsl. */
enum {
    LOC_LIGHT_VIEW = 6,
    LOC_FLUID_COLOR = 7,
    LOC_ABSORPTION = 8,
    LOC_FRESNEL_F0 = 9,
    LOC_REFRACTION_STRENGTH = 10,
    LOC_EDGE_THICKNESS = 11
};
/* Texture units fixed by layout(binding) in composite.frag.glsl. */
enum { UNIT_SURFACE_DEPTH = 0, UNIT_THICKNESS = 1, UNIT_BACKGROUND = 2 };

fc_code fc_composite_pass_create(const char *shader_dir, fc_composite_pass *pass, fc_error *err)
{
    *pass = (fc_composite_pass){
        .srgb_target = fc_render_target_init(GL_SRGB8_ALPHA8, false, false),
        .float_target = fc_render_target_init(GL_RGBA32F, false, false),
    };
    glCreateVertexArrays(1, &pass->empty_vertex_array);
    const char *files[] = {"fullscreen.vert.glsl", "camera.frag.glsl", "environment.frag.glsl",
                           "composite.frag.glsl"};
    return fc_program_build(shader_dir, files, sizeof files / sizeof files[0], &pass->program, err);
}

void fc_composite_pass_destroy(fc_composite_pass *pass)
{
    glDeleteProgram(pass->program);
    glDeleteVertexArrays(1, &pass->empty_vertex_array);
    fc_render_target_release(&pass->srgb_target);
    fc_render_target_release(&pass->float_target);
    pass->program = pass->empty_vertex_array = 0;
}

/* Schlick's reflectance at normal incidence for a fluid of index `ior` in air. */
static float fresnel_f0(float ior)
{
    float r = (ior - 1.0f) / (ior + 1.0f);
    return r * r;
}

static void apply_material(const fc_settings *settings)
{
    glUniform3fv(LOC_FLUID_COLOR, 1, settings->fluid_color);
    glUniform3fv(LOC_ABSORPTION, 1, settings->absorption);
    glUniform1f(LOC_FRESNEL_F0, fresnel_f0(settings->ior));
    /* γ of eq. 15 from the index of refraction: for small angles a ray bends by
     * about (1 - 1/ior) times the surface tilt, so the background seen through
     * a layer of thickness T shifts by about that much per unit of T. */
    glUniform1f(LOC_REFRACTION_STRENGTH, 1.0f - 1.0f / settings->ior);
    glUniform1f(LOC_EDGE_THICKNESS, settings->radius);
}

fc_code fc_composite_pass_run(fc_composite_pass *pass, const fc_composite_inputs *in, const fc_view *view,
                              const fc_environment *env, const fc_settings *settings, bool want_u8,
                              const fc_render_target **result, fc_error *err)
{
    fc_render_target *target = want_u8 ? &pass->srgb_target : &pass->float_target;
    fc_code code = fc_render_target_resize(target, view->width, view->height, err);
    if (code != FC_OK)
        return code;
    fc_render_target_bind(target);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    /* The shader works in linear RGB; the sRGB target encodes on write. */
    if (want_u8)
        glEnable(GL_FRAMEBUFFER_SRGB);
    else
        glDisable(GL_FRAMEBUFFER_SRGB);
    glUseProgram(pass->program);
    fc_environment_apply(env, view);
    glUniform3fv(LOC_LIGHT_VIEW, 1, env->light_view);
    apply_material(settings);
    glBindTextureUnit(UNIT_SURFACE_DEPTH, in->surface_depth->color);
    glBindTextureUnit(UNIT_THICKNESS, in->thickness->color);
    glBindTextureUnit(UNIT_BACKGROUND, in->background->color);
    fc_gl_draw_fullscreen(pass->empty_vertex_array);
    glDisable(GL_FRAMEBUFFER_SRGB);
    *result = target;
    return fc_gl_check("composite pass", err);
}
