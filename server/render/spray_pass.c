/* spray_pass.c — spray droplets blended over the composite. */
#include "spray_pass.h"

#include "gl_util.h"

/* Uniform locations fixed by layout(location) in spray.frag.glsl. */
enum {
    LOC_LIGHT_VIEW = 10,
    LOC_FLUID_COLOR = 11,
    LOC_WHITENING = 12,
    LOC_SPEED_REFERENCE = 13
};
/* Droplets are smaller than the fluid's particles: spray is separate drops,
 * not blobs. The sprites span this fraction of the radius; spray.frag.glsl
 * draws each droplet between 0.45 and 1 of its sprite. */
#define DROPLET_RADIUS_FRACTION 0.7f

fc_code fc_spray_pass_create(const char *shader_dir, fc_spray_pass *pass, fc_error *err)
{
    return fc_sphere_sprites_create_shaped(shader_dir, "particle_attributes.frag.glsl", "spray.frag.glsl",
                                           &pass->sprites, err);
}

void fc_spray_pass_destroy(fc_spray_pass *pass)
{
    fc_sphere_sprites_destroy(&pass->sprites);
}

static void set_uniforms(GLuint program, const fc_environment *env, const fc_settings *settings)
{
    glProgramUniform3fv(program, LOC_LIGHT_VIEW, 1, env->light_view);
    glProgramUniform3fv(program, LOC_FLUID_COLOR, 1, settings->fluid_color);
    glProgramUniform1f(program, LOC_WHITENING, settings->foam);
    /* A droplet moving as fast as the velocity change that counts as violent is half-way to white. */
    glProgramUniform1f(program, LOC_SPEED_REFERENCE, settings->foam_tau);
}

fc_code fc_spray_pass_run(fc_spray_pass *pass, const fc_particle_buffer *particles, uint64_t first,
                          const fc_particle_attributes *attributes, const fc_view *view, const fc_environment *env,
                          const fc_settings *settings, const fc_render_target *target, fc_error *err)
{
    if (first >= particles->count)
        return FC_OK;
    fc_render_target_bind(target);
    /* Hidden behind fluid or floor; droplets do not hide one another, they blend. */
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
    if (target->color_format == GL_SRGB8_ALPHA8)
        glEnable(GL_FRAMEBUFFER_SRGB);
    set_uniforms(fc_sphere_sprites_program(&pass->sprites, particles), env, settings);
    fc_particle_attributes_bind(attributes);
    fc_sphere_sprites_draw_range(&pass->sprites, particles, first, particles->count - first, view,
                                 DROPLET_RADIUS_FRACTION * settings->radius);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glDisable(GL_BLEND);
    glDepthMask(GL_TRUE);
    glDisable(GL_DEPTH_TEST);
    return fc_gl_check("spray pass", err);
}
