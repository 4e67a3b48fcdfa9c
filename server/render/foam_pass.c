/* foam_pass.c — see foam_pass.h. */
#include "foam_pass.h"

#include <stdlib.h>

#include "fc_error.h"
#include "gl_util.h"

/* Uniform locations fixed by layout(location) in foam.frag.glsl. */
enum { LOC_LIGHT_VIEW = 10 };
/* Binding of the foam particles' looks in foam.frag.glsl. */
#define LOOKS_BINDING 18
/* A foam disc's radius per particle radius, before its own size: a little
 * wider than the particle, so neighbouring discs merge into one patch. */
#define FOAM_RADIUS_FRACTION 1.7f
/* The sizes of the discs, as factors of that radius: [smallest, largest). */
#define FOAM_SMALLEST 0.6f
#define FOAM_LARGEST 1.4f
/* The opacity of a disc whose potential just passes the threshold, and the
 * potential (in thresholds) at which a disc is as opaque as the setting
 * allows: the patch fades out where the flow traps less air. */
#define FOAM_FAINTEST 0.0f
#define FOAM_FULL_AT 1.25f
/* Foam is a patch, not flecks: a foam particle with at most FOAM_LONE foam
 * neighbours is not drawn (a lone disc would be a ghost blob), one with
 * FOAM_CROWD more than that at full opacity, fainter in proportion between. */
#define FOAM_LONE 1u
#define FOAM_CROWD 2.0f
/* The most a single disc covers at its centre, at strength 1: a patch is
 * white where several overlap. */
#define FOAM_DISC_OPACITY 0.9f

fc_code fc_foam_pass_create(const char *shader_dir, fc_foam_pass *pass, fc_error *err)
{
    *pass = (fc_foam_pass){0};
    fc_code code = fc_sphere_sprites_create_with(shader_dir, NULL, "foam.frag.glsl", &pass->sprites, err);
    if (code == FC_OK)
        code = fc_particle_buffer_create(&pass->particles, err);
    return code;
}

void fc_foam_pass_destroy(fc_foam_pass *pass)
{
    fc_sphere_sprites_destroy(&pass->sprites);
    fc_particle_buffer_destroy(&pass->particles);
    if (pass->looks)
        glDeleteBuffers(1, &pass->looks);
    *pass = (fc_foam_pass){0};
}

void fc_foam_pass_clear(fc_foam_pass *pass)
{
    pass->particles.count = 0;
    pass->filled_generation = 0;
}

/* A uniform number in [0, 1) from a particle's id (Wang's integer hash), so
 * a particle keeps its disc's size from frame to frame. */
static float hash_unit(uint32_t id)
{
    id = (id ^ 61u) ^ (id >> 16);
    id *= 9u;
    id ^= id >> 4;
    id *= 0x27d4eb2du;
    id ^= id >> 15;
    return (float)(id >> 8) / 16777216.0f;
}

static float clampf(float x, float lo, float hi)
{
    return x < lo ? lo : x > hi ? hi : x;
}

/* Packs the drawn foam particles' positions and looks (size, opacity) in
 * frame order; returns how many. */
static uint64_t pack_foam(const fc_foam_classes *foam, const fc_frame *frame, float strength, float *positions,
                      float *looks)
{
    uint64_t n = 0;
    for (uint64_t i = 0; i < frame->count; i++) {
        if (!foam->foam[i] || foam->company[i] <= FOAM_LONE)
            continue;
        for (int k = 0; k < 3; k++)
            positions[3 * n + k] = frame->positions[3 * i + k];
        float size = FOAM_SMALLEST + (FOAM_LARGEST - FOAM_SMALLEST) * hash_unit(frame->ids ? frame->ids[i]
                                                                                             : (uint32_t)i);
        float above = clampf((foam->potential[i] / foam->threshold - 1.0f) / (FOAM_FULL_AT - 1.0f), 0.0f, 1.0f);
        float crowd = clampf((float)(foam->company[i] - FOAM_LONE) / FOAM_CROWD, 0.0f, 1.0f);
        float opacity = FOAM_DISC_OPACITY * strength * crowd * (FOAM_FAINTEST + (1.0f - FOAM_FAINTEST) * above);
        looks[4 * n] = size / FOAM_LARGEST;   /* of the sprite, which reaches the largest disc */
        looks[4 * n + 1] = clampf(opacity, 0.0f, 1.0f);
        looks[4 * n + 2] = looks[4 * n + 3] = 0.0f;
        n++;
    }
    return n;
}

static fc_code upload_looks(fc_foam_pass *pass, const float *looks, uint64_t count, fc_error *err)
{
    GLsizeiptr bytes = (GLsizeiptr)(count * 4 * sizeof *looks);
    if (!pass->looks)
        glCreateBuffers(1, &pass->looks);
    if (count > pass->look_capacity) {
        glNamedBufferData(pass->looks, bytes, looks, GL_DYNAMIC_DRAW);
        pass->look_capacity = count;
    } else {
        glNamedBufferSubData(pass->looks, 0, bytes, looks);
    }
    return fc_gl_check("foam looks", err);
}

fc_code fc_foam_pass_fill(fc_foam_pass *pass, const fc_foam_classes *foam, const fc_frame *frame, uint64_t generation,
                          float strength, fc_error *err)
{
    if (pass->filled_generation == generation && pass->filled_strength == strength)
        return FC_OK;
    fc_foam_pass_clear(pass);
    uint64_t count = foam->count;
    if (count > 0) {
        float *positions = malloc(count * 3 * sizeof *positions), *looks = malloc(count * 4 * sizeof *looks);
        fc_code code = positions && looks ? FC_OK
                                          : fc_error_set(err, FC_ERR_NOMEM, "out of memory for %llu foam particles",
                                                         (unsigned long long)count);
        count = code == FC_OK ? pack_foam(foam, frame, strength, positions, looks) : 0;
        fc_frame packed = {.count = count, .positions = positions};
        if (count > 0)
            code = fc_particle_buffer_upload(&pass->particles, &packed, err);
        if (code == FC_OK && count > 0)
            code = upload_looks(pass, looks, count, err);
        free(positions);
        free(looks);
        if (code != FC_OK) {
            fc_foam_pass_clear(pass);
            return code;
        }
    }
    pass->filled_generation = generation;
    pass->filled_strength = strength;
    return FC_OK;
}

fc_code fc_foam_pass_run(fc_foam_pass *pass, const fc_view *view, const fc_environment *env, float radius,
                         const fc_render_target *target, fc_error *err)
{
    if (pass->particles.count == 0)
        return FC_OK;
    /* Hidden behind fluid or floor; discs do not hide one another, they blend. */
    fc_render_target_bind_overlay(target);
    glProgramUniform3fv(fc_sphere_sprites_program(&pass->sprites, &pass->particles), LOC_LIGHT_VIEW, 1,
                        env->light_view);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, LOOKS_BINDING, pass->looks);
    /* The sprites reach the largest disc; the shader draws each its own size. */
    fc_sphere_sprites_draw(&pass->sprites, &pass->particles, view, FOAM_RADIUS_FRACTION * FOAM_LARGEST * radius);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glDisable(GL_BLEND);
    glDepthMask(GL_TRUE);
    glDisable(GL_DEPTH_TEST);
    return fc_gl_check("foam pass", err);
}
