/* shadow_pass.c — see shadow_pass.h. */
#include "shadow_pass.h"

#include <math.h>

#include "anisotropy.h"
#include "gl_util.h"
#include "shader_program.h"
#include "vec3.h"
#include "view.h"

/* Texels per side of the map: the shadow is soft, so a coarse map serves,
 * and the splat's cost grows with its area (bench/RESULTS.md). */
#define MAP_SIZE 256u
/* The blur of the map, in its texels: the penumbra of a sun about a degree
 * across at the distances splashes stand above their floor. */
#define MAP_BLUR 2u
/* The sun's camera stands this many box radii away, looking at the box:
 * rays from it are parallel within about half a degree, so a shadow falls
 * where parallel sunlight puts it (at 20 radii they leaned up to three
 * degrees at the box's edges and shadows landed 6% too far out). */
#define SUN_DISTANCE_RADII 100.0f
/* Light leaves the sun's beam through water by absorption (the fluid's
 * own, per channel) and by refraction at its surfaces, which bends it out
 * of the beam whatever its colour: this much per particle radius. */
#define REFRACTED_OUT_PER_RADIUS 0.3f
/* Texels of the map around the particles' box where the splat, blur and box
 * may still leave thickness (a sprite's conservative bounds, MAP_BLUR, the
 * box and two bilinear lookups take fewer than half of these). */
#define SHADOW_REACH_TEXELS 16.0f
/* The thickness is splatted at this share of the map's resolution, where it
 * is blurred in any case: a quarter of the texels (64k particles: 8 of 43
 * CPU ms; the shadow the same by eye, a mean of 0.0001 per channel), and the
 * same with and without meshes. */
#define THICKNESS_SCALE 0.5f

/* Uniform locations fixed by layout(location) in shadow_box.frag.glsl. */
enum { LOC_BOX_TEXEL = 0, LOC_BOX_LAST = 1 };

fc_code fc_shadow_pass_create(const char *shader_dir, fc_shadow_pass *pass, fc_error *err)
{
    pass->box = fc_render_target_init(GL_R32F, false, true);
    glCreateVertexArrays(1, &pass->empty_vertex_array);
    const char *box[] = {"fullscreen.vert.glsl", "shadow_box.frag.glsl"};
    fc_code code = fc_program_build(shader_dir, box, sizeof box / sizeof box[0], &pass->box_program, err);
    if (code == FC_OK)
        code = fc_depth_pass_create(shader_dir, &pass->splat, err);
    return code == FC_OK ? fc_thickness_pass_create(shader_dir, &pass->blur, err) : code;
}

void fc_shadow_pass_destroy(fc_shadow_pass *pass)
{
    fc_depth_pass_destroy(&pass->splat);
    fc_thickness_pass_destroy(&pass->blur);
    fc_render_target_release(&pass->box);
    glDeleteProgram(pass->box_program);
    glDeleteVertexArrays(1, &pass->empty_vertex_array);
    pass->box_program = pass->empty_vertex_array = 0;
}

/* The 4x4-texel box of `map` into pass->box, of the same size (so of the
 * same texture size: both only grow, from the same requests). */
static fc_code box_map(fc_shadow_pass *pass, const fc_render_target *map, fc_error *err)
{
    fc_code code = fc_render_target_resize(&pass->box, map->width, map->height, err);
    if (code != FC_OK)
        return code;
    fc_render_target_bind(&pass->box);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glUseProgram(pass->box_program);
    float texel[2] = {1.0f / (float)map->texture_width, 1.0f / (float)map->texture_height};
    glUniform2f(LOC_BOX_TEXEL, texel[0], texel[1]);
    glUniform2f(LOC_BOX_LAST, ((float)map->width - 0.5f) * texel[0], ((float)map->height - 0.5f) * texel[1]);
    glBindTextureUnit(0, map->color);
    fc_gl_draw_fullscreen(pass->empty_vertex_array);
    return fc_gl_check("shadow map box", err);
}

/* A camera on the sun's side of the box, framing its bounding sphere. */
static void sun_camera(const float lo[3], const float hi[3], float radius, const float sun[3], fc_camera *cam)
{
    float centre[3], half[3];
    for (int i = 0; i < 3; i++) {
        centre[i] = 0.5f * (lo[i] + hi[i]);
        half[i] = 0.5f * (hi[i] - lo[i]);
    }
    float extent = sqrtf(fc_dot3(half, half)) + radius;
    float distance = SUN_DISTANCE_RADII * extent;
    /* Any direction not along the sun serves as up: the map is square. */
    float up[3] = {0.0f, 0.0f, 1.0f};
    if (fabsf(sun[2]) > 0.9f)
        up[0] = 1.0f, up[2] = 0.0f;
    *cam = (fc_camera){.fov_y_deg = (float)(2.0 * atan(1.02 * extent / distance) * 180.0 / 3.14159265358979),
                       .width = MAP_SIZE, .height = MAP_SIZE};
    for (int i = 0; i < 3; i++) {
        cam->eye[i] = centre[i] + distance * sun[i];
        cam->target[i] = centre[i];
        cam->up[i] = up[i];
    }
}

/* The world box the shadow comes from: the particles' grown by their reach
 * and by SHADOW_REACH_TEXELS of the map (which spans about 2.04 extents). */
static void shadow_box(const float lo[3], const float hi[3], float reach, fc_environment *env)
{
    float half[3] = {0.5f * (hi[0] - lo[0]), 0.5f * (hi[1] - lo[1]), 0.5f * (hi[2] - lo[2])};
    float extent = sqrtf(fc_dot3(half, half)) + reach;
    float grow = reach + SHADOW_REACH_TEXELS * 2.04f * extent / (float)MAP_SIZE;
    for (int i = 0; i < 3; i++) {
        env->shadow_box_lo[i] = lo[i] - grow;
        env->shadow_box_hi[i] = hi[i] + grow;
    }
}

/* World point -> (u w, v w, 0, w) with (u, v) in [0, 1] over the map:
 * uv = 0.5 ndc + 0.5 and ndc = f x / w, w the distance in front of the sun's
 * camera. Column-major like fc_view.view. */
static void map_transform(const fc_view *v, float m[16])
{
    for (int c = 0; c < 4; c++) {
        float x = v->view[c * 4 + 0], y = v->view[c * 4 + 1], w = -v->view[c * 4 + 2];
        m[c * 4 + 0] = 0.5f * v->fx * x + 0.5f * w;
        m[c * 4 + 1] = 0.5f * v->fy * y + 0.5f * w;
        m[c * 4 + 2] = 0.0f;
        m[c * 4 + 3] = w;
    }
}

/* The fluid's nearest depth from the sun, for meshes (environment.frag.glsl's
 * in_front_of_fluid, which only mesh_shade.frag.glsl reaches); none without. */
static void set_fluid_sun_depth(const fc_shadow_pass *pass, bool with_depth, fc_environment *env)
{
    const fc_render_target *t = &pass->splat.target;
    env->fluid_sun_depth = with_depth ? t->color : 0;
    env->fluid_sun_depth_uv_scale[0] = with_depth ? (float)t->width / (float)t->texture_width : 0.0f;
    env->fluid_sun_depth_uv_scale[1] = with_depth ? (float)t->height / (float)t->texture_height : 0.0f;
}

/* The sun's camera for these particles, at the map's resolution. */
static void sun_view(const fc_particle_buffer *particles, const float lo[3], const float hi[3],
                     const fc_settings *settings, const float sun[3], fc_view *view)
{
    /* Ellipsoids may reach past the radius: the sun's view must hold them whole. */
    float reach = fc_anisotropy_reach(particles, settings->radius);
    fc_camera cam;
    sun_camera(lo, hi, reach, sun, &cam);
    fc_view_from_camera(&cam, lo, hi, reach, view);
}

fc_view fc_shadow_pass_thickness_view(const fc_particle_buffer *particles, const float lo[3], const float hi[3],
                                      const fc_settings *settings, const fc_environment *env)
{
    fc_view view;
    sun_view(particles, lo, hi, settings, env->sun, &view);
    return fc_thickness_view(&view, THICKNESS_SCALE);
}

fc_render_target *fc_shadow_pass_thickness(fc_shadow_pass *pass)
{
    return &pass->splat.thickness;
}

fc_code fc_shadow_pass_run(fc_shadow_pass *pass, const fc_particle_buffer *particles, const float lo[3],
                           const float hi[3], const fc_settings *settings, bool with_depth, bool splatted,
                           fc_pass_profile *profile, fc_environment *env, fc_error *err)
{
    fc_view view;
    sun_view(particles, lo, hi, settings, env->sun, &view);
    float reach = fc_anisotropy_reach(particles, settings->radius);
    static const float no_floor[4] = {0.0f, 0.0f, 0.0f, 1.0f};   /* nothing is cut off */
    /* The sun's depth (for meshes) at the map's resolution, alone; the
     * thickness at THICKNESS_SCALE of it. */
    fc_code code = FC_OK;
    if (with_depth) {
        fc_pass_profile_begin(profile, "shadow depth splat");
        code = fc_depth_pass_run(&pass->splat, particles, &view, settings->radius, NULL, err);
        fc_pass_profile_end(profile);
    }
    fc_thickness_params params = {.radius = settings->radius, .scale = THICKNESS_SCALE, .blur = MAP_BLUR,
                                  .floor_plane = no_floor, .profile = profile, .splat_name = "shadow splat",
                                  .depth = &pass->splat, .splatted = splatted};
    const fc_render_target *blurred = NULL;
    if (code == FC_OK)
        code = fc_thickness_pass_run(&pass->blur, particles, &view, &params, &blurred, err);
    if (code == FC_OK) {
        fc_pass_profile_begin(profile, "shadow box");
        code = box_map(pass, blurred, err);
        fc_pass_profile_end(profile);
    }
    if (code != FC_OK)
        return code;
    map_transform(&view, env->shadow_transform);
    shadow_box(lo, hi, reach, env);
    /* The map may fill only the lower-left part of its texture (targets only grow). */
    const fc_render_target *map = &pass->box;
    env->shadow_uv_scale[0] = (float)map->width / (float)map->texture_width;
    env->shadow_uv_scale[1] = (float)map->height / (float)map->texture_height;
    env->shadow_uv_last[0] = ((float)map->width - 0.5f) / (float)map->texture_width;
    env->shadow_uv_last[1] = ((float)map->height - 0.5f) / (float)map->texture_height;
    env->shadow_map = map->color;
    env->has_shadow = true;
    set_fluid_sun_depth(pass, with_depth, env);
    pass->sun_view = view;
    for (int c = 0; c < 3; c++)
        env->shadow_extinction[c] = (settings->absorption[c] + REFRACTED_OUT_PER_RADIUS) / settings->radius;
    return FC_OK;
}

void fc_shadow_pass_tally(const fc_shadow_pass *pass, fc_gpu_memory *m)
{
    fc_depth_pass_tally(&pass->splat, m);
    fc_thickness_pass_tally(&pass->blur, m);
    fc_render_target_tally(&pass->box, m);
}

void fc_shadow_pass_trim(fc_shadow_pass *pass)
{
    fc_depth_pass_trim(&pass->splat);
    fc_thickness_pass_trim(&pass->blur);
    fc_render_target_release(&pass->box);
}
