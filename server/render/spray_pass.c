/* spray_pass.c — spray droplets blended over the composite. */
#include "spray_pass.h"

#include <math.h>
#include <stdbool.h>
#include <stdlib.h>

#include "fc_error.h"
#include "gl_util.h"

/* Uniform locations fixed by layout(location) in spray.frag.glsl. */
enum {
    LOC_LIGHT_VIEW = 10,
    LOC_FLUID_COLOR = 11,
    LOC_WHITENING = 12,
    LOC_SPEED_REFERENCE = 13,
    LOC_FIRST_SPRAY = 14,
    LOC_MEAN_SPEED = 15,
    LOC_STREAK_ROOM = 16
};
/* Binding of the droplets' velocities in spray.frag.glsl. */
#define VELOCITIES_BINDING 17
/* Droplets are smaller than the fluid's particles: spray is separate drops,
 * not blobs. The sprites span this fraction of the radius; spray.frag.glsl
 * draws each droplet between 0.45 and 1 of its sprite. */
#define DROPLET_RADIUS_FRACTION 0.7f

fc_code fc_spray_pass_create(const char *shader_dir, fc_spray_pass *pass, fc_error *err)
{
    *pass = (fc_spray_pass){0};
    return fc_sphere_sprites_create_shaped(shader_dir, "particle_attributes.frag.glsl", "spray.frag.glsl",
                                           &pass->sprites, err);
}

void fc_spray_pass_destroy(fc_spray_pass *pass)
{
    fc_sphere_sprites_destroy(&pass->sprites);
    if (pass->velocities)
        glDeleteBuffers(1, &pass->velocities);
    pass->velocities = 0;
    pass->velocity_capacity = 0;
}

/* The mean speed of the frame's particles: what "fast" means for this flow,
 * whatever its units and time step. */
static float mean_speed(const fc_frame *frame)
{
    double sum = 0.0;
    for (uint64_t i = 0; i < frame->count; i++) {
        const float *v = frame->velocity + 3 * i;
        sum += sqrt((double)v[0] * v[0] + (double)v[1] * v[1] + (double)v[2] * v[2]);
    }
    return frame->count ? (float)(sum / (double)frame->count) : 0.0f;
}

/* Writes the world velocities of the droplets in draw slots first.. into the
 * pass's buffer (grown as needed) and binds it. */
static fc_code upload_velocities(fc_spray_pass *pass, const fc_particle_attributes *attributes,
                                 const fc_frame *frame, uint64_t first, uint64_t count, fc_error *err)
{
    float *packed = malloc(count * 4 * sizeof *packed);
    if (!packed)
        return fc_error_set(err, FC_ERR_NOMEM, "out of memory for %llu spray velocities", (unsigned long long)count);
    const uint32_t *order = fc_particle_attributes_draw_order(attributes);
    for (uint64_t s = 0; s < count; s++) {
        uint64_t i = order ? order[first + s] : first + s;
        for (int k = 0; k < 3; k++)
            packed[4 * s + k] = frame->velocity[3 * i + k];
        packed[4 * s + 3] = 0.0f;
    }
    if (!pass->velocities)
        glCreateBuffers(1, &pass->velocities);
    if (count > pass->velocity_capacity) {
        glNamedBufferData(pass->velocities, (GLsizeiptr)(count * 4 * sizeof *packed), packed, GL_DYNAMIC_DRAW);
        pass->velocity_capacity = count;
    } else {
        glNamedBufferSubData(pass->velocities, 0, (GLsizeiptr)(count * 4 * sizeof *packed), packed);
    }
    free(packed);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, VELOCITIES_BINDING, pass->velocities);
    return fc_gl_check("spray velocities", err);
}

static void set_uniforms(GLuint program, const fc_environment *env, const fc_settings *settings, uint64_t first,
                         float mean, float room)
{
    glProgramUniform3fv(program, LOC_LIGHT_VIEW, 1, env->light_view);
    glProgramUniform3fv(program, LOC_FLUID_COLOR, 1, settings->fluid_color);
    glProgramUniform1f(program, LOC_WHITENING, settings->foam);
    /* A droplet moving as fast as the velocity change that counts as violent is half-way to white. */
    glProgramUniform1f(program, LOC_SPEED_REFERENCE, settings->foam_tau);
    glProgramUniform1i(program, LOC_FIRST_SPRAY, (GLint)first);
    glProgramUniform1f(program, LOC_MEAN_SPEED, mean);
    glProgramUniform1f(program, LOC_STREAK_ROOM, room);
}

fc_code fc_spray_pass_run(fc_spray_pass *pass, const fc_particle_buffer *particles, uint64_t first,
                          const fc_particle_attributes *attributes, const fc_frame *frame, const fc_view *view,
                          const fc_environment *env, const fc_settings *settings, const fc_render_target *target,
                          fc_error *err)
{
    if (first >= particles->count)
        return FC_OK;
    uint64_t count = particles->count - first;
    /* With velocities the sprites have room for the longest streak; the
     * shader draws each droplet within it (room 1: round droplets). */
    bool streaks = frame->velocity != NULL && frame->count == particles->count;
    float room = streaks ? FC_SPRAY_MAX_STREAK : 1.0f;
    float mean = streaks ? mean_speed(frame) : 0.0f;
    if (streaks) {
        fc_code code = upload_velocities(pass, attributes, frame, first, count, err);
        if (code != FC_OK)
            return code;
    }
    /* Hidden behind fluid or floor; droplets do not hide one another, they blend. */
    fc_render_target_bind_overlay(target);
    set_uniforms(fc_sphere_sprites_program(&pass->sprites, particles), env, settings, first, mean, room);
    fc_particle_attributes_bind(attributes);
    fc_sphere_sprites_draw_range(&pass->sprites, particles, first, count, view,
                                 DROPLET_RADIUS_FRACTION * settings->radius * room);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glDisable(GL_BLEND);
    glDepthMask(GL_TRUE);
    glDisable(GL_DEPTH_TEST);
    return fc_gl_check("spray pass", err);
}
