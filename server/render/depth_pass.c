/* depth_pass.c — nearest sphere depth and summed thickness in one splat. */
#include "depth_pass.h"

#include <math.h>

#include "anisotropy.h"
#include "fc_error.h"
#include "gl_util.h"
#include "pinhole_fill.h"
#include "shader_program.h"

/* Uniform location fixed by layout(location) in thickness_chord.glsl. */
enum { LOC_FLOOR_PLANE = 10, LOC_SOURCE_SIZE = 52 };
enum { UNIT_SPLAT_DEPTH = 0 };

/* The compute splat wins while a typical sprite (at the depth of the
 * particles' centre) is at most this many pixels across. Measured on
 * llvmpipe with the pass's wall and CPU time (bench/RESULTS.md, "The splat
 * and the smoothing on llvmpipe", 2026-12-02): the compute splat took less
 * of both at every size tried up to the largest-sprite limit below (16 px:
 * 28 against 35 ms wall, 35 px: 39 against 48, 55 px: 33 against 82), as it
 * runs on every rasterizer thread while the point sprites' set-up is serial.
 * Earlier rounds put the crossover at 11, then 14 px, measured as the whole
 * process's CPU time before the pinhole fill. */
#define COMPUTE_SPLAT_MAX_TYPICAL_PX 64.0f
/* The compute splat is used only while no sprite can be wider than this.
 * One invocation walks a whole sprite, and llvmpipe ends every invocation's
 * loops after 65535 iterations in all (gallivm's loop limiter): a sprite of
 * 256x256 pixels would be cut off. 160 stays far below that (25,600 pixels),
 * and spares the other invocations of a SIMD group the wait for one large
 * sprite. */
#define COMPUTE_SPLAT_MAX_LARGEST_PX 160.0f

fc_code fc_depth_pass_create(const char *shader_dir, fc_depth_pass *pass, fc_error *err)
{
    *pass = (fc_depth_pass){
        .raw = fc_render_target_init(GL_R32F, false, false),
        .thickness = fc_render_target_init(GL_R32F, false, true),
        .target = fc_render_target_init(GL_R32F, false, false),
        .method = FC_SPLAT_AUTO,
        .last_used = FC_SPLAT_FRAGMENT,
    };
    glCreateVertexArrays(1, &pass->empty_vertex_array);
    glCreateFramebuffers(1, &pass->splat_framebuffer);
    const char *resolve[] = {"fullscreen.vert.glsl", "pinhole_fill.glsl", "depth_resolve.frag.glsl"};
    fc_code code = fc_sphere_sprites_create_shaped(shader_dir, "thickness_chord.glsl", "surface_splat.frag.glsl",
                                                   &pass->sprites, err);
    if (code == FC_OK)
        code = fc_program_build(shader_dir, resolve, sizeof resolve / sizeof resolve[0], &pass->resolve_program,
                                err);
    if (code == FC_OK)
        code = fc_compute_splat_create(shader_dir, &pass->compute, err);
    return code;
}

void fc_depth_pass_destroy(fc_depth_pass *pass)
{
    fc_sphere_sprites_destroy(&pass->sprites);
    fc_compute_splat_destroy(&pass->compute);
    glDeleteProgram(pass->resolve_program);
    glDeleteVertexArrays(1, &pass->empty_vertex_array);
    glDeleteFramebuffers(1, &pass->splat_framebuffer);
    fc_render_target_release(&pass->raw);
    fc_render_target_release(&pass->thickness);
    fc_render_target_release(&pass->target);
    pass->resolve_program = pass->empty_vertex_array = pass->splat_framebuffer = 0;
}

/* Sizes the splat's two images and (with_depth) the linear depth to the
 * view; the splat framebuffer follows the textures when they are reallocated. */
static fc_code resize(fc_depth_pass *pass, const fc_view *view, bool with_depth, fc_error *err)
{
    GLuint raw = pass->raw.color, thickness = pass->thickness.color;
    fc_code code = fc_render_target_resize(&pass->raw, view->width, view->height, err);
    if (code == FC_OK)
        code = fc_render_target_resize(&pass->thickness, view->width, view->height, err);
    if (code == FC_OK && with_depth)
        code = fc_render_target_resize(&pass->target, view->width, view->height, err);
    if (code != FC_OK || (raw == pass->raw.color && thickness == pass->thickness.color))
        return code;
    glNamedFramebufferTexture(pass->splat_framebuffer, GL_COLOR_ATTACHMENT0, pass->raw.color, 0);
    glNamedFramebufferTexture(pass->splat_framebuffer, GL_COLOR_ATTACHMENT1, pass->thickness.color, 0);
    GLenum status = glCheckNamedFramebufferStatus(pass->splat_framebuffer, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        return fc_error_set(err, FC_ERR_GL, "surface splat framebuffer %ux%u incomplete: status 0x%04x",
                            view->width, view->height, (unsigned)status);
    return fc_gl_check("attaching the surface splat images", err);
}

/* Nearest depth (with_depth) by GL_MIN on attachment 0, thickness (with a
 * floor plane) by addition on 1. */
static void splat(fc_depth_pass *pass, const fc_particle_buffer *particles, const fc_view *view, float radius,
                  const float *floor_plane, bool with_depth)
{
    const GLenum attachments[2] = {with_depth ? GL_COLOR_ATTACHMENT0 : GL_NONE,
                                   floor_plane ? GL_COLOR_ATTACHMENT1 : GL_NONE};
    glNamedFramebufferDrawBuffers(pass->splat_framebuffer, 2, attachments);
    glBindFramebuffer(GL_FRAMEBUFFER, pass->splat_framebuffer);
    glViewport(0, 0, (GLsizei)view->width, (GLsizei)view->height);
    const GLfloat nothing_yet = INFINITY, no_thickness = 0.0f;
    if (with_depth)
        glClearNamedFramebufferfv(pass->splat_framebuffer, GL_COLOR, 0, &nothing_yet);
    if (floor_plane)
        glClearNamedFramebufferfv(pass->splat_framebuffer, GL_COLOR, 1, &no_thickness);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glEnable(GL_BLEND);
    glBlendEquationi(0, GL_MIN);
    glBlendEquationi(1, GL_FUNC_ADD);
    glBlendFunc(GL_ONE, GL_ONE);
    if (floor_plane)
        glProgramUniform4fv(fc_sphere_sprites_program(&pass->sprites, particles), LOC_FLOOR_PLANE, 1, floor_plane);
    fc_sphere_sprites_draw(&pass->sprites, particles, view, radius);
    glBlendEquation(GL_FUNC_ADD);
    glDisable(GL_BLEND);
}

/* Pixels across of a sphere of `radius` whose centre is `depth` in front of
 * the camera: 2 r f / depth in NDC, half the image height per NDC unit. */
static float sprite_px(const fc_view *view, float radius, float depth)
{
    return radius * view->fy * (float)view->height / depth;
}

/* The widest any sphere inside the bounds can be on screen, in pixels: at
 * the nearest depth they allow, and stretched by 1 + tan² of the angle off
 * the view axis, up to the image's corners, as a sphere's silhouette is
 * towards the edges. */
static float largest_sprite_px(const fc_view *view, float radius)
{
    float stretch = 1.0f + 1.0f / (view->fx * view->fx) + 1.0f / (view->fy * view->fy);
    /* The near plane hugs the nearest corner of the bounds grown by the radius (view.h). */
    return stretch * sprite_px(view, radius, view->near_plane + radius);
}

/* Pixels across of a sphere at the depth of the bounds' centre; 0 where that lies behind the eye. */
static float typical_sprite_px(const fc_view *view, const float lo[3], const float hi[3], float radius)
{
    const float *m = view->view;   /* column-major: view z of a point is row 2 */
    float centre_depth = -(m[2] * 0.5f * (lo[0] + hi[0]) + m[6] * 0.5f * (lo[1] + hi[1]) +
                           m[10] * 0.5f * (lo[2] + hi[2]) + m[14]);
    return centre_depth > 0.0f ? sprite_px(view, radius, centre_depth) : 0.0f;
}

fc_splat_method fc_depth_pass_choose(const fc_view *view, const float lo[3], const float hi[3], float radius,
                                     fc_splat_method wanted)
{
    if (wanted == FC_SPLAT_FRAGMENT || largest_sprite_px(view, radius) > COMPUTE_SPLAT_MAX_LARGEST_PX)
        return FC_SPLAT_FRAGMENT;
    if (wanted == FC_SPLAT_COMPUTE)
        return FC_SPLAT_COMPUTE;
    float typical = typical_sprite_px(view, lo, hi, radius);
    return typical > 0.0f && typical <= COMPUTE_SPLAT_MAX_TYPICAL_PX ? FC_SPLAT_COMPUTE : FC_SPLAT_FRAGMENT;
}

static fc_code fragment_splat(fc_depth_pass *pass, const fc_particle_buffer *particles, const fc_view *view,
                              float radius, const float *floor_plane, bool with_depth, fc_error *err)
{
    splat(pass, particles, view, radius, floor_plane, with_depth);
    if (!with_depth)
        return fc_gl_check("thickness splat", err);
    fc_render_target_bind(&pass->target);
    fc_pinhole_fill_apply(pass->resolve_program, view, radius);
    glProgramUniform2i(pass->resolve_program, LOC_SOURCE_SIZE, (GLint)view->width, (GLint)view->height);
    glUseProgram(pass->resolve_program);
    glBindTextureUnit(UNIT_SPLAT_DEPTH, pass->raw.color);
    fc_gl_draw_fullscreen(pass->empty_vertex_array);
    return fc_gl_check("depth pass", err);
}

/* The splat for these particles in this view: fc_depth_pass_choose for
 * the radius and, for ellipsoids, their longest reach. Ellipsoids are
 * chosen for by the radius, as their exact boxes are mostly about as large
 * as the sphere's (the compute splat measured 120-130 ms against the
 * fragment splat's 150-290 at 64k particles 10 px across, bench/RESULTS.md),
 * but the largest sprite must hold for the longest reach. */
static fc_splat_method choose(const fc_depth_pass *pass, const fc_particle_buffer *particles, const fc_view *view,
                              float radius)
{
    fc_splat_method choice = fc_depth_pass_choose(view, particles->lo, particles->hi, radius, pass->method);
    float reach = fc_anisotropy_reach(particles, radius);
    if (choice == FC_SPLAT_COMPUTE &&
        fc_depth_pass_choose(view, particles->lo, particles->hi, reach, FC_SPLAT_COMPUTE) == FC_SPLAT_FRAGMENT)
        choice = FC_SPLAT_FRAGMENT;
    return choice;
}

/* How large the particles appear in the view, for the compute splat's walk. */
static fc_splat_sprite sprite_in(const fc_view *view, const fc_particle_buffer *particles, float radius)
{
    float reach = fc_anisotropy_reach(particles, radius);
    return (fc_splat_sprite){largest_sprite_px(view, reach),
                             typical_sprite_px(view, particles->lo, particles->hi, reach)};
}

static fc_code run(fc_depth_pass *pass, const fc_particle_buffer *particles, const fc_view *view, float radius,
                   const float *floor_plane, bool with_depth, fc_error *err)
{
    fc_code code = resize(pass, view, with_depth, err);
    if (code != FC_OK)
        return code;
    pass->last_used = choose(pass, particles, view, radius);
    if (pass->last_used == FC_SPLAT_COMPUTE)
        return fc_compute_splat_run(&pass->compute, particles, view, radius, sprite_in(view, particles, radius),
                                    floor_plane, with_depth ? pass->target.color : 0, pass->thickness.color, err);
    return fragment_splat(pass, particles, view, radius, floor_plane, with_depth, err);
}

fc_code fc_depth_pass_run(fc_depth_pass *pass, const fc_particle_buffer *particles, const fc_view *view,
                          float radius, const float *floor_plane, fc_error *err)
{
    return run(pass, particles, view, radius, floor_plane, true, err);
}

fc_code fc_depth_pass_run_thickness(fc_depth_pass *pass, const fc_particle_buffer *particles, const fc_view *view,
                                    float radius, const float *floor_plane, fc_error *err)
{
    if (!floor_plane)
        return fc_error_set(err, FC_ERR_USAGE, "thickness splat without a floor plane");
    return run(pass, particles, view, radius, floor_plane, false, err);
}

bool fc_depth_pass_fuses(const fc_depth_pass *pass, const fc_particle_buffer *particles, const fc_view *view,
                         const fc_view *thickness_view, float radius)
{
    return choose(pass, particles, view, radius) == FC_SPLAT_COMPUTE &&
           fc_compute_splat_fuses(&pass->compute, particles, sprite_in(thickness_view, particles, radius));
}

bool fc_depth_pass_fuses_sun(const fc_depth_pass *pass, const fc_particle_buffer *particles,
                             const fc_view *sun_view, float radius)
{
    return fc_compute_splat_fuses_sun(&pass->compute, particles, sprite_in(sun_view, particles, radius));
}

fc_code fc_depth_pass_run_fused(fc_depth_pass *pass, const fc_particle_buffer *particles, const fc_view *view,
                                const fc_view *thickness_view, float radius, const float *floor_plane,
                                const fc_depth_sun *sun, fc_error *err)
{
    if (!floor_plane || !fc_depth_pass_fuses(pass, particles, view, thickness_view, radius) ||
        (sun && !fc_depth_pass_fuses_sun(pass, particles, sun->view, radius)))
        return fc_error_set(err, FC_ERR_USAGE, "fused depth splat: no floor plane, or the particles do not fuse");
    fc_code code = resize(pass, view, true, err);
    if (code == FC_OK)
        code = fc_render_target_resize(&pass->thickness, thickness_view->width, thickness_view->height, err);
    if (code == FC_OK && sun)
        code = fc_render_target_resize(sun->thickness, sun->view->width, sun->view->height, err);
    if (code != FC_OK)
        return code;
    pass->last_used = FC_SPLAT_COMPUTE;
    fc_sun_splat sun_splat = {sun ? sun->view : NULL, sun ? sun->thickness->color : 0};
    return fc_compute_splat_run_fused(&pass->compute, particles, view, thickness_view, radius,
                                      sprite_in(view, particles, radius), floor_plane, pass->target.color,
                                      pass->thickness.color, sun ? &sun_splat : NULL, err);
}

void fc_depth_pass_tally(const fc_depth_pass *pass, fc_gpu_memory *m)
{
    fc_render_target_tally(&pass->raw, m);
    fc_render_target_tally(&pass->thickness, m);
    fc_render_target_tally(&pass->target, m);
    fc_compute_splat_tally(&pass->compute, m);
}

void fc_depth_pass_trim(fc_depth_pass *pass)
{
    fc_render_target_release(&pass->raw);
    fc_render_target_release(&pass->thickness);
    fc_render_target_release(&pass->target);
    fc_compute_splat_trim(&pass->compute);
}
