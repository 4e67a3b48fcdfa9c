/* pipeline.c — the screen-space fluid pipeline: orchestrates the passes of
 * pipeline.h for one request, timing each stage on the GPU. */
#include "pipeline.h"

#include <epoxy/gl.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "anisotropy.h"
#include "background_pass.h"
#include "color_values.h"
#include "composite_pass.h"
#include "depth_pass.h"
#include "environment.h"
#include "fc_colormap.h"
#include "fc_error.h"
#include "fc_frame.h"
#include "foam_classes.h"
#include "foam_pass.h"
#include "gl_util.h"
#include "mesh_pass.h"
#include "noise_pass.h"
#include "normal_pass.h"
#include "particle_attributes.h"
#include "particle_buffer.h"
#include "pass_profile.h"
#include "pipeline_internal.h"
#include "readback.h"
#include "scene_textures.h"
#include "shadow_pass.h"
#include "smoothing.h"
#include "spray_classes.h"
#include "spray_pass.h"
#include "stage_timer.h"
#include "surface_mesher.h"
#include "surface_passes.h"
#include "surface_raster.h"
#include "thickness_pass.h"
#include "view.h"

/* Neighbouring pixels whose depths differ by more than this many particle
 * radii belong to separate surfaces: smoothing must not bridge them. Steps
 * between the spheres of one surface stay below about two radii. */
#define DEPTH_JUMP_RADII 4.0f

struct fc_pipeline {
    fc_particle_buffer particles;         /* in draw order: the frame's, or surface particles first, then spray */
    fc_particle_attributes attributes;
    fc_spray_classes spray_classes;       /* the sort keys that split the spray off (spray_classes.h) */
    uint64_t classes_upload;              /* the upload spray_classes was computed for; 0: none */
    uint32_t classes_neighbours;          /* and its spray_neighbours */
    fc_foam_classes foam_classes;         /* the aerated surface particles (foam_classes.h) */
    uint64_t foam_upload;                 /* the upload foam_classes was computed for; 0: none */
    uint32_t foam_neighbours;             /* and its spray_neighbours */
    uint64_t foam_generation;             /* counts the foam classes computed: what the foam pass was filled from */
    fc_color_values color_values;         /* the attribute colour_by names, for renders that colour */
    uint64_t uploads;                     /* frames uploaded so far: what the colour values were filled for */
    float estimated_radius;               /* fc_frame_estimate_radius of the uploaded frame, */
    uint64_t estimated_upload;            /* for this upload; 0: none yet */
    fc_anisotropy anisotropy;             /* the particles' ellipsoids, for FC_KERNEL_ANISOTROPIC */
    bool uploaded;
    fc_frame frame;                       /* the uploaded frame's arrays, which the caller keeps (pipeline.h) */
    fc_depth_pass depth;
    fc_thickness_pass thickness;
    fc_smoother smoother;
    fc_noise_pass noise;
    fc_normal_pass normal;
    fc_background_pass background;
    fc_composite_pass composite;
    fc_spray_pass spray;
    fc_foam_pass foam;
    fc_shadow_pass shadow;
    fc_mesh_pass mesh;
    fc_stage_timer timer;
    fc_pass_profile profile;
    fc_readback readback;
    GLint max_image_size;   /* largest width or height the GPU renders */
    char *shader_dir;       /* fc_pipeline_config.shader_dir (NULL: built in), for the passes built on first use */
    fc_surface_passes surface;   /* surface mesh extraction (surface_extract.h), built by its first use */
    bool surface_built;
    fc_surface_raster raster;    /* --surface mesh: the frame's mesh and its depth, built by its first use */
    bool raster_built;
};

/* One request as the stages see it. */
typedef struct render_job {
    const fc_view *view;
    const fc_settings *settings;
    const fc_scene_textures *scene;   /* NULL: the built-in scene */
    const fc_scene_mesh *meshes;
    uint32_t mesh_count;
    float lo[3], hi[3];               /* the particles' box grown by the meshes': the floor and the sun frame it */
    fc_environment env;
    fc_particle_buffer surface;       /* the pipeline's particles without the spray (a prefix of them) */
    bool want_u8;
    bool colored;                     /* the colour image, tinted by settings->color_by */
} render_job;

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

static GLint query_max_image_size(void)
{
    GLint texture = 0, viewport[2] = {0, 0};
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &texture);
    glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
    GLint size = texture < viewport[0] ? texture : viewport[0];
    return size < viewport[1] ? size : viewport[1];
}

/* Whether the full-screen passes take their uniforms as flat inputs: where
 * uniforms are costly to read (llvmpipe, flat_constants.h), or as told. */
static bool uses_flat_constants(const fc_pipeline_config *config)
{
    fc_constants_path path = config ? config->constants : FC_CONSTANTS_AUTO;
    return path == FC_CONSTANTS_FLAT || (path == FC_CONSTANTS_AUTO && fc_gl_software_rasterizer());
}

static fc_code create_passes(fc_pipeline *p, const char *dir, bool flat, fc_error *err)
{
    p->readback = fc_readback_init();
    fc_code code = fc_particle_buffer_create(&p->particles, err);
    if (code == FC_OK)
        code = fc_particle_attributes_create(&p->attributes, err);
    if (code == FC_OK)
        code = fc_anisotropy_create(dir, &p->anisotropy, err);
    if (code == FC_OK)
        code = fc_depth_pass_create(dir, &p->depth, err);
    if (code == FC_OK)
        code = fc_thickness_pass_create(dir, &p->thickness, err);
    if (code == FC_OK)
        code = fc_shadow_pass_create(dir, &p->shadow, err);
    if (code == FC_OK)
        code = fc_smoother_create(dir, &p->smoother, err);
    if (code == FC_OK)
        code = fc_noise_pass_create(dir, &p->noise, err);
    if (code == FC_OK)
        code = fc_normal_pass_create(dir, &p->normal, err);
    if (code == FC_OK)
        code = fc_background_pass_create(dir, flat, &p->background, err);
    if (code == FC_OK)
        code = fc_mesh_pass_create(dir, &p->mesh, err);
    if (code == FC_OK)
        code = fc_composite_pass_create(dir, flat, &p->composite, err);
    if (code == FC_OK)
        code = fc_spray_pass_create(dir, &p->spray, err);
    if (code == FC_OK)
        code = fc_foam_pass_create(dir, &p->foam, err);
    if (code == FC_OK)
        code = fc_stage_timer_create(&p->timer, err);
    if (code == FC_OK)
        code = fc_pass_profile_create(&p->profile, err);
    return code;
}

/* Whether the depth pass splats the thickness too: at full resolution, when
 * the image needs thickness without a colour (the thickness pass splats the
 * two together). */
static bool splats_thickness(const render_job *job, fc_aov aov)
{
    return job->settings->thickness_scale == 1.0f && !job->colored &&
           (aov == FC_AOV_COLOR || aov == FC_AOV_THICKNESS);
}

/* Whether the depth stage splats the thickness at its reduced scale too, in
 * the same walk of the particles (fc_depth_pass_fuses): for a colour image
 * without an attribute's colour. */
static bool fuses_thickness(const fc_pipeline *p, const render_job *job, fc_aov aov)
{
    if (job->settings->thickness_scale == 1.0f || job->colored || aov != FC_AOV_COLOR)
        return false;
    fc_view reduced = fc_thickness_view(job->view, job->settings->thickness_scale);
    return fc_depth_pass_fuses(&p->depth, &job->surface, job->view, &reduced, job->settings->radius);
}

/* Whether the composite runs the shadow pass, and that without meshes (the
 * sun's view then needs no depth of the fluid). */
static bool shadow_without_meshes(const render_job *job)
{
    return job->settings->shadow && job->env.has_floor && job->mesh_count == 0;
}

/* What the depth stage splatted besides the depth. */
typedef struct depth_extras {
    bool thickness;   /* the camera's thickness: the thickness stage only blurs it */
    bool sun;         /* the shadow map's: the shadow pass only blurs it */
} depth_extras;

/* Depth, and the thickness splat where splats_thickness or fuses_thickness,
 * with the shadow map's thickness where that fuses too (*extras says which):
 * all are timed as the depth stage. */
static fc_code mesh_depth_stage(fc_pipeline *p, const render_job *job, depth_extras *extras, fc_error *err);

static fc_code depth_stage(fc_pipeline *p, const render_job *job, fc_aov aov, depth_extras *extras, fc_error *err)
{
    if (job->settings->surface == FC_SURFACE_MODE_MESH)
        return mesh_depth_stage(p, job, extras, err);
    bool together = splats_thickness(job, aov), fused = !together && fuses_thickness(p, job, aov);
    float radius = job->settings->radius;
    fc_view sun_view = {0};
    if (fused && shadow_without_meshes(job)) {
        sun_view = fc_shadow_pass_thickness_view(&job->surface, job->lo, job->hi, job->settings, &job->env);
        extras->sun = fc_depth_pass_fuses_sun(&p->depth, &job->surface, &sun_view, radius);
    }
    extras->thickness = together || fused;
    fc_stage_timer_begin(&p->timer, FC_STAGE_DEPTH);
    fc_pass_profile_begin(&p->profile, extras->sun         ? "depth + thickness + shadow splat"
                                       : extras->thickness ? "depth + thickness splat"
                                                           : "depth splat");
    fc_code code;
    if (fused) {
        fc_view reduced = fc_thickness_view(job->view, job->settings->thickness_scale);
        fc_depth_sun sun = {&sun_view, fc_shadow_pass_thickness(&p->shadow)};
        code = fc_depth_pass_run_fused(&p->depth, &job->surface, job->view, &reduced, radius, job->env.floor_plane,
                                       extras->sun ? &sun : NULL, err);
    } else {
        code = fc_depth_pass_run(&p->depth, &job->surface, job->view, radius,
                                 together ? job->env.floor_plane : NULL, err);
    }
    fc_pass_profile_end(&p->profile);
    /* Fluid behind an opaque mesh is not there for any later stage. */
    if (code == FC_OK && job->mesh_count > 0) {
        fc_pass_profile_begin(&p->profile, "mesh occlusion");
        code = fc_mesh_pass_occlude(&p->mesh, job->meshes, job->mesh_count, job->view, &p->depth.target, err);
        fc_pass_profile_end(&p->profile);
    }
    fc_stage_timer_end(&p->timer, FC_STAGE_DEPTH);
    return code;
}

/* --surface mesh: the frame's surface mesh rasterised into the depth and
 * (at the thickness pass's scale) the thickness the splats would have made,
 * then cut by the opaque meshes like the splats' depth. The thickness of a
 * colour by attribute, which carries the particles' colours, and the sun's
 * are splatted from the particles by their own stages. */
static fc_code mesh_depth_stage(fc_pipeline *p, const render_job *job, depth_extras *extras, fc_error *err)
{
    fc_stage_timer_begin(&p->timer, FC_STAGE_DEPTH);
    fc_pass_profile_begin(&p->profile, "surface mesh depth");
    fc_code code = fc_surface_raster_depth(&p->raster, job->view, &p->depth.target, err);
    fc_pass_profile_end(&p->profile);
    extras->thickness = !job->colored;
    if (code == FC_OK && extras->thickness) {
        fc_view reduced = fc_thickness_view(job->view, job->settings->thickness_scale);
        fc_pass_profile_begin(&p->profile, "surface mesh thickness");
        code = fc_surface_raster_thickness(&p->raster, &reduced, &p->depth.thickness, err);
        fc_pass_profile_end(&p->profile);
    }
    if (code == FC_OK && job->mesh_count > 0) {
        fc_pass_profile_begin(&p->profile, "mesh occlusion");
        code = fc_mesh_pass_occlude(&p->mesh, job->meshes, job->mesh_count, job->view, &p->depth.target, err);
        fc_pass_profile_end(&p->profile);
    }
    fc_stage_timer_end(&p->timer, FC_STAGE_DEPTH);
    return code;
}

/* The map's entries as linear RGB, which the shaders interpolate. */
static void linear_colormap(fc_colormap map, float out[FC_COLORMAP_ENTRIES][3])
{
    const float(*table)[3] = fc_colormap_table(map);
    for (int i = 0; i < FC_COLORMAP_ENTRIES; i++)
        for (int c = 0; c < 3; c++)
            out[i][c] = fc_srgb_to_linear(table[i][c]);
}

/* The thickness: splatted here at reduced resolution, else (`splatted`) by
 * the depth stage, which must have run first; blurred and resampled here, to
 * the view's size for the thickness AOV. */
static fc_code thickness_stage(fc_pipeline *p, const render_job *job, fc_aov aov, bool splatted,
                               const fc_render_target **result, fc_error *err)
{
    const fc_settings *s = job->settings;
    fc_thickness_params params = {
        .radius = s->radius,
        .scale = s->thickness_scale,
        .blur = s->thickness_blur,
        .floor_plane = job->env.floor_plane,
        .profile = &p->profile,
        .depth = &p->depth,
        .at_view_size = aov == FC_AOV_THICKNESS,
        .splatted = splatted,
    };
    float colormap[FC_COLORMAP_ENTRIES][3];
    fc_thickness_color color = {&p->color_values, {s->color_range[0], s->color_range[1]}, colormap};
    if (job->colored) {
        linear_colormap(s->colormap, colormap);
        params.color = &color;
    }
    fc_stage_timer_begin(&p->timer, FC_STAGE_THICKNESS);
    fc_code code = fc_thickness_pass_run(&p->thickness, &job->surface, job->view, &params, result, err);
    fc_stage_timer_end(&p->timer, FC_STAGE_THICKNESS);
    return code;
}

static fc_code run_noise(fc_pipeline *p, const render_job *job, const fc_render_target *surface, fc_error *err)
{
    fc_pass_profile_begin(&p->profile, "noise splat");
    fc_code code = fc_noise_pass_run(&p->noise, &job->surface, &p->attributes, surface, job->view,
                                     job->settings->radius, job->settings->noise, err);
    fc_pass_profile_end(&p->profile);
    return code;
}

static fc_code smoothing_stage(fc_pipeline *p, const fc_view *view, const fc_settings *s,
                               const fc_render_target **surface, fc_error *err)
{
    fc_smoothing_params params = {
        .method = s->smoothing,
        .iterations = s->iterations,
        .depth_jump = DEPTH_JUMP_RADII * s->radius,
        .particle_radius = s->radius,
        .filter_radius = s->filter_radius,
        /* Near and far hug the particles: their middle is a typical fluid depth. */
        .reference_depth = 0.5f * (view->near_plane + view->far_plane),
        .smooth_scale = s->smooth_scale,
        .profile = &p->profile,
    };
    fc_view_pixel_scale(view, &params.pixel_scale[0], &params.pixel_scale[1]);
    bool runs = s->smoothing != FC_SMOOTHING_NONE && s->iterations > 0;
    if (runs)
        fc_stage_timer_begin(&p->timer, FC_STAGE_SMOOTHING);
    fc_code code = fc_smoother_run(&p->smoother, &p->depth.target, &params, surface, err);
    if (runs)
        fc_stage_timer_end(&p->timer, FC_STAGE_SMOOTHING);
    return code;
}

/* The noise texture shading reads, NULL without noise: the splats are then
 * skipped, not summed to 0. */
static fc_code shading_noise(fc_pipeline *p, const render_job *job, const fc_render_target *surface,
                             const fc_render_target **noise, fc_error *err)
{
    *noise = NULL;
    if (!(job->settings->noise > 0.0f))
        return FC_OK;
    *noise = &p->noise.target;
    return run_noise(p, job, surface, err);
}

/* Noise, background and spray are rendered for the composite alone, so they
 * are timed with it. */
static fc_code composite_stage(fc_pipeline *p, const render_job *job, const fc_render_target *surface,
                               const fc_render_target *thickness, bool sun_splatted, const fc_render_target **result,
                               fc_error *err)
{
    fc_composite_inputs inputs = {surface, thickness, &p->background.target, NULL,
                                  job->scene ? job->scene->environment_map : 0, job->colored,
                                  fc_mesh_any_opaque(job->meshes, job->mesh_count), false};
    /* The background pass lays down the composite's mask where the driver
     * lets it and no opaque mesh must be tested against (one full-screen
     * pass fewer on a CPU rasterizer). */
    inputs.masked = !inputs.depth_tested && fc_background_pass_writes_mask(&p->background);
    bool want_u8 = job->want_u8;
    fc_environment env = job->env;   /* the shadow pass adds its map */
    fc_stage_timer_begin(&p->timer, FC_STAGE_COMPOSITE);
    fc_code code = shading_noise(p, job, surface, &inputs.noise, err);
    fc_pass_profile *profile = &p->profile;
    if (code == FC_OK && job->settings->shadow && env.has_floor)
        code = fc_shadow_pass_run(&p->shadow, &job->surface, job->lo, job->hi, job->settings, job->mesh_count > 0,
                                  sun_splatted, profile, &env, err);
    if (code == FC_OK && env.has_shadow && job->mesh_count > 0) {
        fc_pass_profile_begin(profile, "mesh shadows");
        code = fc_mesh_pass_cast_shadows(&p->mesh, job->meshes, job->mesh_count, &p->shadow.sun_view, &env, err);
        fc_pass_profile_end(profile);
    }
    const fc_render_target *target = NULL;
    if (code == FC_OK)
        code = fc_composite_pass_target(&p->composite, job->view, want_u8, &target, err);
    if (code == FC_OK) {
        fc_pass_profile_begin(profile, "background");
        code = fc_background_pass_run(&p->background, job->view, &env, job->scene,
                                      inputs.masked ? surface : NULL, target, err);
        fc_pass_profile_end(profile);
    }
    if (code == FC_OK && job->mesh_count > 0) {
        fc_pass_profile_begin(profile, "opaque meshes");
        code = fc_mesh_pass_draw_opaque(&p->mesh, job->meshes, job->mesh_count, job->view, &env,
                                        &p->background.target, target, want_u8, err);
        fc_pass_profile_end(profile);
    }
    if (code == FC_OK) {
        fc_pass_profile_begin(profile, "composite");
        code = fc_composite_pass_run(&p->composite, &inputs, job->view, &env, job->settings, want_u8, result, err);
        fc_pass_profile_end(profile);
    }
    if (code == FC_OK && p->foam.particles.count > 0) {
        fc_pass_profile_begin(profile, "foam");
        code = fc_foam_pass_run(&p->foam, job->view, &job->env, job->settings->radius, *result, err);
        fc_pass_profile_end(profile);
    }
    if (code == FC_OK) {
        fc_pass_profile_begin(profile, "spray");
        code = fc_spray_pass_run(&p->spray, &p->particles, job->surface.count, &p->attributes, &p->frame, job->view,
                                 &job->env, job->settings, *result, err);
        fc_pass_profile_end(profile);
    }
    if (code == FC_OK && job->mesh_count > 0) {
        fc_pass_profile_begin(profile, "glass meshes");
        code = fc_mesh_pass_draw_glass(&p->mesh, job->meshes, job->mesh_count, job->view, &env, *result, want_u8, err);
        fc_pass_profile_end(profile);
    }
    if (code == FC_OK) {
        fc_pass_profile_begin(profile, "silhouette blend");
        code = fc_smoother_blend_silhouettes(&p->smoother, *result, want_u8, result, err);
        fc_pass_profile_end(profile);
    }
    fc_stage_timer_end(&p->timer, FC_STAGE_COMPOSITE);
    return code;
}

/* The noise or normal image: the composite's inputs on their own, timed as its stage. */
static fc_code shading_aov_stage(fc_pipeline *p, const render_job *job, const fc_render_target *surface, fc_aov aov,
                                 const fc_render_target **result, fc_error *err)
{
    fc_stage_timer_begin(&p->timer, FC_STAGE_COMPOSITE);
    fc_code code;
    if (aov == FC_AOV_NOISE) {
        code = run_noise(p, job, surface, err);
        *result = &p->noise.target;
    } else {
        const fc_render_target *noise = NULL;
        code = shading_noise(p, job, surface, &noise, err);
        if (code == FC_OK)
            code = fc_normal_pass_run(&p->normal, surface, noise, job->view, job->settings->radius, result, err);
    }
    fc_stage_timer_end(&p->timer, FC_STAGE_COMPOSITE);
    return code;
}

/* Runs the stages the requested image needs, no more, and sets *result to the
 * target holding it. */
static fc_code render_stages(fc_pipeline *p, const render_job *job, fc_aov aov, const fc_render_target **result,
                             fc_error *err)
{
    depth_extras splatted = {false, false};
    if (aov == FC_AOV_THICKNESS) {
        bool depth_first = splats_thickness(job, aov) || job->settings->surface == FC_SURFACE_MODE_MESH;
        fc_code code = depth_first ? depth_stage(p, job, aov, &splatted, err) : FC_OK;
        return code == FC_OK ? thickness_stage(p, job, aov, splatted.thickness, result, err) : code;
    }
    fc_code code = depth_stage(p, job, aov, &splatted, err);
    *result = &p->depth.target;
    if (code != FC_OK || aov == FC_AOV_DEPTH)
        return code;
    const fc_render_target *surface = NULL;
    code = smoothing_stage(p, job->view, job->settings, &surface, err);
    *result = surface;
    if (code != FC_OK || aov == FC_AOV_SMOOTHED_DEPTH)
        return code;
    if (aov == FC_AOV_NOISE || aov == FC_AOV_NORMAL)
        return shading_aov_stage(p, job, surface, aov, result, err);
    const fc_render_target *thickness = NULL;
    code = thickness_stage(p, job, aov, splatted.thickness, &thickness, err);
    if (code != FC_OK)
        return code;
    return composite_stage(p, job, surface, thickness, splatted.sun, result, err);
}

/* The particles' box, grown to hold the meshes. */
static void scene_bounds(const fc_pipeline *p, const fc_render_scene *scene, float lo[3], float hi[3])
{
    for (int k = 0; k < 3; k++) {
        lo[k] = p->particles.lo[k];
        hi[k] = p->particles.hi[k];
    }
    if (scene->meshes)
        fc_mesh_bounds(scene->meshes, scene->mesh_count, lo, hi);
}

/* The job of a validated request: the view, the surface particles (all but
 * the spray) and the scene around them. */
static void plan_job(const fc_pipeline *p, const fc_view *view, const fc_camera *camera, const fc_settings *settings,
                     const fc_render_scene *scene, fc_aov aov, bool want_u8, render_job *job)
{
    *job = (render_job){.view = view, .settings = settings, .scene = scene->textures, .meshes = scene->meshes,
                        .mesh_count = scene->meshes ? scene->mesh_count : 0, .surface = p->particles,
                        .want_u8 = want_u8,
                        .colored = aov == FC_AOV_COLOR && settings->color_by != FC_COLOR_BY_NONE};
    job->surface.count = fc_particle_attributes_surface_count(&p->attributes, fc_spray_classes_threshold(settings));
    scene_bounds(p, scene, job->lo, job->hi);
    bool has_floor = !(scene->textures && scene->textures->background);
    fc_environment_for_view(view, camera, job->lo, job->hi, settings, has_floor, want_u8, &job->env);
}

/* Positions go to the GPU in the frame's order, with their records: each
 * written once, straight into the mapped buffers, once the GPU is done with
 * the last frame's. */
static fc_code upload_frame(fc_pipeline *p, const fc_frame *frame, fc_error *err)
{
    fc_code code = fc_particle_buffer_reserve(&p->particles, frame->count, frame->radius != NULL, err);
    if (code == FC_OK)
        code = fc_particle_buffer_measure_radii(&p->particles, frame, err);
    if (code == FC_OK)
        code = fc_particle_attributes_upload(&p->attributes, frame, err);
    if (code == FC_OK) {
        fc_particle_buffer_fill(&p->particles, frame, NULL);
        p->frame = *frame;
        p->uploads++;
    }
    return code;
}

float fc_pipeline_estimated_radius(fc_pipeline *p)
{
    if (p->estimated_upload != p->uploads || !p->uploaded) {
        p->estimated_radius = fc_frame_estimate_radius(&p->frame);
        p->estimated_upload = p->uploads;
    }
    return p->estimated_radius;
}

/* The neighbourhoods of the spray classes and the anisotropy: the uploaded
 * frame's own spacing, whatever the render radius. */
static float neighbourhood_support(fc_pipeline *p)
{
    return fc_anisotropy_support(fc_pipeline_estimated_radius(p));
}

/* The neighbour classes of the uploaded frame, and the grid they were
 * counted on (which the foam classes walk too). */
static fc_code compute_spray_classes(fc_pipeline *p, uint32_t spray_neighbours, fc_error *err)
{
    float support = spray_neighbours > 0 && !p->frame.radius ? neighbourhood_support(p) : 0.0f;
    fc_pass_profile_begin(&p->profile, "spray classes");
    fc_code code = fc_spray_classes_compute(&p->spray_classes, &p->frame, support, spray_neighbours, err);
    fc_pass_profile_end(&p->profile);
    p->classes_upload = code == FC_OK ? p->uploads : 0;
    p->classes_neighbours = spray_neighbours;
    return code;
}

/* A density threshold or the neighbour classes (spray_classes.h) split the
 * surface from the spray at a prefix of the density order: the uploaded
 * frame is put in that order at the first render that asks for spray, and
 * stays in it until a render asks for other classes: without spray the
 * order changes an image only by the rounding of the thickness sums (depth
 * is a minimum, and ids and amplitudes travel with their particles). */
static fc_code order_for(fc_pipeline *p, const fc_settings *settings, fc_error *err)
{
    fc_particle_attributes *a = &p->attributes;
    if (!(fc_spray_classes_threshold(settings) > 0.0f) || !a->reorderable ||
        (a->by_density && a->ordered_classes == settings->spray_neighbours))
        return FC_OK;
    fc_code code = compute_spray_classes(p, settings->spray_neighbours, err);
    /* Waits for the draws still reading the positions, as well as the records. */
    if (code == FC_OK)
        code = fc_particle_attributes_order_by_density(a, &p->frame, p->spray_classes.keys,
                                                       settings->spray_neighbours, err);
    if (code == FC_OK)
        fc_particle_buffer_fill(&p->particles, &p->frame, fc_particle_attributes_draw_order(a));
    return code;
}

/* The foam of a colour image with aerated_foam (foam_classes.h, foam_pass.h):
 * classified once per upload on the neighbour classes' grid (counted here
 * when the order did not need them), and handed to the foam pass. None
 * (the pass emptied, nothing computed) when the setting is 0, for other
 * images, without velocities, or without neighbour classes. */
static fc_code foam_for(fc_pipeline *p, const fc_settings *settings, fc_aov aov, fc_error *err)
{
    uint32_t neighbours = settings->spray_neighbours;
    if (!(settings->aerated_foam > 0.0f) || aov != FC_AOV_COLOR || !p->frame.velocity || neighbours == 0) {
        fc_foam_pass_clear(&p->foam);
        return FC_OK;
    }
    if (p->foam_upload != p->uploads || p->foam_neighbours != neighbours) {
        fc_code code = FC_OK;
        if (p->classes_upload != p->uploads || p->classes_neighbours != neighbours)
            code = compute_spray_classes(p, neighbours, err);
        fc_pass_profile_begin(&p->profile, "foam classes");
        if (code == FC_OK)
            code = fc_foam_classes_compute(&p->foam_classes, &p->spray_classes, &p->frame, err);
        fc_pass_profile_end(&p->profile);
        if (code != FC_OK)
            return code;
        p->foam_upload = p->uploads;
        p->foam_neighbours = neighbours;
        p->foam_generation++;
    }
    return fc_foam_pass_fill(&p->foam, &p->foam_classes, &p->frame, p->foam_generation, settings->aerated_foam, err);
}

/* The particles' shape for a render: their ellipsoids (computed once per
 * upload and order, whatever the camera and radius) for the anisotropic kernel,
 * named in the particle buffer so every splat of it casts them; else
 * spheres. */
static fc_code shape_particles(fc_pipeline *p, const fc_settings *settings, fc_error *err)
{
    p->particles.shapes = 0;
    if (settings->kernel != FC_KERNEL_ANISOTROPIC)
        return FC_OK;
    fc_pass_profile_begin(&p->profile, "anisotropy");
    fc_code code = fc_anisotropy_update(&p->anisotropy, &p->particles, neighbourhood_support(p), err);
    fc_pass_profile_end(&p->profile);
    if (code == FC_OK)
        p->particles.shapes = p->anisotropy.ellipsoids;
    return code;
}

/* The colour image with color_by set needs the attribute of each particle
 * in draw order (after order_for): INVALID_VALUE when the frame lacks it. */
static fc_code color_particles(fc_pipeline *p, const fc_settings *settings, fc_aov aov, fc_error *err)
{
    if (aov != FC_AOV_COLOR || settings->color_by == FC_COLOR_BY_NONE)
        return FC_OK;
    return fc_color_values_update(&p->color_values, &p->frame, fc_particle_attributes_draw_order(&p->attributes),
                                  settings->color_by, p->uploads, err);
}

/* One warm-up image of the uploaded frame, through every stage its settings use. */
static fc_code warm_up_image(fc_pipeline *p, const fc_camera *camera, const fc_settings *settings, fc_aov aov,
                             fc_error *err)
{
    fc_code code = shape_particles(p, settings, err);
    if (code != FC_OK)
        return code;
    fc_view view;
    fc_view_from_camera(camera, p->particles.lo, p->particles.hi, settings->radius, &view);
    render_job job;
    plan_job(p, &view, camera, settings, &(fc_render_scene){0}, aov, true, &job);
    const fc_render_target *result = NULL;
    return render_stages(p, &job, aov, &result, err);
}

/* The default look (fc_settings_default) twice, as a stream's first two
 * frames (the second splat culls with what the first one left), the second
 * with a fixed kernel (the narrow-range filter's other program). */
static fc_code warm_up_default_look(fc_pipeline *p, const fc_camera *camera, float radius, fc_error *err)
{
    fc_settings settings;
    fc_settings_default(&settings);
    settings.radius = radius;
    fc_code code = warm_up_image(p, camera, &settings, FC_AOV_COLOR, err);
    settings.filter_radius = 5;
    return code == FC_OK ? warm_up_image(p, camera, &settings, FC_AOV_COLOR, err) : code;
}

/* Renders tiny images through every stage and shading option. Drivers
 * compile shader variants lazily at the first draw (and the background and
 * composite passes build theirs for the features a render uses,
 * shader_variants.h), and some (llvmpipe) report a bogus duration for the
 * first timer query of a context; warming up keeps both out of the first
 * real request. Its 8x8 images are 9x9 textures (fc_gl_non_pot), which
 * llvmpipe compiles the same variants for as for any real size: a particle
 * and a spray droplet with the default look, as a stream's first two frames
 * (sprites a few pixels across: the compute splat's rows walk, as scenes of
 * thousands of particles show them), then with noise and foam, the normal
 * image, and ellipsoids. */
static fc_code warm_up(fc_pipeline *p, fc_error *err)
{
    float positions[6] = {0.0f, 0.0f, 0.0f, 1.5f, 0.0f, 0.0f};
    float density[2] = {1.0f, 0.0f};
    fc_frame frame = {.count = 2, .positions = positions, .density = density};
    fc_camera camera = {.eye = {0.0f, 0.0f, 4.0f}, .up = {0.0f, 1.0f, 0.0f}, .fov_y_deg = 40.0f,
                        .width = 8, .height = 8};
    fc_settings settings = {.radius = 1.0f, .smoothing = FC_SMOOTHING_CURVATURE, .iterations = 1,
                            .smooth_scale = 1.0f, .ior = 1.33f, .shininess = 1.0f, .thickness_scale = 0.5f,
                            .thickness_blur = 1, .foam_tau = 1.0f, .density_threshold = 0.5f, .shadow = 1};
    fc_code code = upload_frame(p, &frame, err);
    if (code == FC_OK)
        code = order_for(p, &settings, err);
    fc_particle_attributes_settle(&p->attributes);
    if (code == FC_OK)
        code = warm_up_default_look(p, &camera, settings.radius, err);
    /* The last image with the anisotropic kernel, for its programs. */
    const fc_aov images[] = {FC_AOV_COLOR, FC_AOV_NORMAL, FC_AOV_COLOR};
    for (size_t i = 0; i < sizeof images / sizeof images[0] && code == FC_OK; i++) {
        settings.kernel = i == 2 ? FC_KERNEL_ANISOTROPIC : FC_KERNEL_SPHERE;
        /* The first image has the default look's features (its shader
         * variants, shader_variants.h), the others noise and foam. */
        settings.noise = settings.foam = i == 0 ? 0.0f : 1.0f;
        code = warm_up_image(p, &camera, &settings, images[i], err);
    }
    for (int s = 0; s < FC_STAGE_COUNT; s++)
        fc_stage_timer_ms(&p->timer, (fc_stage)s);   /* waits until the GPU is done */
    p->particles.count = 0;
    p->particles.shapes = 0;
    p->particles.has_radii = p->particles.sized = false;
    fc_anisotropy_trim(&p->anisotropy);   /* a pipeline holds no ellipsoids until a render asks for them */
    fc_shadow_pass_trim(&p->shadow);      /* nor a shadow map */
    p->attributes.count = 0;
    p->attributes.reorderable = false;
    p->frame = (fc_frame){0};   /* the warm-up's frame dies here */
    return code;
}

fc_code fc_pipeline_create(const fc_pipeline_config *config, fc_pipeline **out, fc_error *err)
{
    if (!out)
        return fc_error_set(err, FC_ERR_USAGE, "fc_pipeline_create: no output");
    *out = NULL;
    fc_pipeline *p = calloc(1, sizeof *p);
    if (!p)
        return fc_error_set(err, FC_ERR_NOMEM, "out of memory for the pipeline");
    const char *dir = config ? config->shader_dir : NULL;
    if (dir && !(p->shader_dir = strdup(dir))) {
        free(p);
        return fc_error_set(err, FC_ERR_NOMEM, "out of memory for the pipeline");
    }
    fc_code code = create_passes(p, dir, uses_flat_constants(config), err);
    if (code == FC_OK)
        code = warm_up(p, err);
    if (code != FC_OK) {
        fc_pipeline_destroy(p);
        return code;
    }
    p->max_image_size = query_max_image_size();
    *out = p;
    return FC_OK;
}

void fc_pipeline_destroy(fc_pipeline *p)
{
    if (!p)
        return;
    fc_readback_release(&p->readback);
    fc_pass_profile_destroy(&p->profile);
    fc_stage_timer_destroy(&p->timer);
    fc_spray_pass_destroy(&p->spray);
    fc_foam_pass_destroy(&p->foam);
    fc_foam_classes_free(&p->foam_classes);
    fc_spray_classes_free(&p->spray_classes);
    fc_composite_pass_destroy(&p->composite);
    fc_background_pass_destroy(&p->background);
    fc_mesh_pass_destroy(&p->mesh);
    fc_normal_pass_destroy(&p->normal);
    fc_noise_pass_destroy(&p->noise);
    fc_smoother_destroy(&p->smoother);
    fc_thickness_pass_destroy(&p->thickness);
    fc_shadow_pass_destroy(&p->shadow);
    fc_depth_pass_destroy(&p->depth);
    fc_anisotropy_destroy(&p->anisotropy);
    fc_surface_passes_destroy(&p->surface);
    fc_surface_raster_destroy(&p->raster);
    fc_color_values_release(&p->color_values);
    fc_particle_attributes_destroy(&p->attributes);
    fc_particle_buffer_destroy(&p->particles);
    free(p->shader_dir);
    free(p);
}

fc_code fc_pipeline_upload(fc_pipeline *p, const fc_frame *frame, float *stage_ms, fc_error *err)
{
    if (!p || !frame || (frame->count > 0 && !frame->positions))
        return fc_error_set(err, FC_ERR_USAGE, "fc_pipeline_upload: missing pipeline or positions");
    /* The upload is the GL thread's copying into mapped buffers, which a GPU
     * timer does not see (and reading one would wait for the GPU): timed by
     * the clock instead. */
    double start = now_ms();
    fc_code code = upload_frame(p, frame, err);
    p->uploaded = code == FC_OK;
    if (stage_ms)
        *stage_ms = code == FC_OK ? (float)(now_ms() - start) : -1.0f;
    return code;
}

static fc_code check_request(const fc_pipeline *p, const fc_camera *camera, const fc_settings *settings,
                             fc_aov aov, fc_error *err)
{
    if (!p->uploaded)
        return fc_error_set(err, FC_ERR_BAD_STATE, "render before any frame was uploaded");
    fc_code code = fc_camera_validate(camera, err);
    if (code == FC_OK)
        code = fc_settings_validate(settings, err);
    if (code != FC_OK)
        return code;
    if (fc_radius_source_of(settings, p->particles.has_radii) == FC_RADIUS_ESTIMATED)
        return fc_error_set(err, FC_ERR_INVALID_VALUE,
                            "radius %g: the pipeline needs a resolved radius > 0 for a frame without radii",
                            (double)settings->radius);
    if (aov < FC_AOV_COLOR || aov > FC_AOV_NOISE)
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "unknown image kind (aov) %d", (int)aov);
    if (camera->width > (uint32_t)p->max_image_size || camera->height > (uint32_t)p->max_image_size)
        return fc_error_set(err, FC_ERR_RENDER, "image %ux%u exceeds this GPU's limit of %d pixels per side",
                            camera->width, camera->height, (int)p->max_image_size);
    return FC_OK;
}

static void report_stages(const fc_stage_timer *timer, float *stage_ms)
{
    if (!stage_ms)
        return;
    for (int s = 0; s < FC_STAGE_COUNT; s++)
        stage_ms[s] = fc_stage_timer_ms(timer, (fc_stage)s);
}

/* Channels of each image kind as read back. */
static uint32_t channels_of(fc_aov aov)
{
    return aov == FC_AOV_COLOR ? 4 : aov == FC_AOV_NORMAL ? 3 : 1;
}

/* The settings the stages see: a radius of 0 on a frame with radii sizes
 * each particle by its own (PROTOCOL.md 5), the median standing for them
 * where one size is needed; a radius > 0 overrides them. */
/* --surface mesh: the uploaded frame's mesh, extracted unless the raster
 * holds it already for this upload and these settings. The anisotropic
 * kernel's ellipsoids upload the frame again (fc_pipeline_frame_ellipsoids),
 * before any render step orders the particles. */
static fc_code prepare_surface_mesh(fc_pipeline *p, const fc_settings *settings, fc_error *err)
{
    if (!p->raster_built) {
        fc_code code = fc_surface_raster_create(p->shader_dir, &p->raster, err);
        if (code != FC_OK) {
            fc_surface_raster_destroy(&p->raster);
            return code;
        }
        p->raster_built = true;
    }
    if (fc_surface_raster_holds(&p->raster, p->uploads, settings))
        return FC_OK;
    const fc_surface_passes *passes;
    fc_code code = fc_surface_mesher_check(&p->frame, settings, err);
    if (code == FC_OK)
        code = fc_pipeline_surface_passes(p, &passes, err);
    fc_ellipsoid *ellipsoids = NULL;
    if (code == FC_OK && settings->surface_kernel == FC_SURFACE_KERNEL_ANISOTROPIC) {
        ellipsoids = malloc((size_t)p->frame.count * sizeof *ellipsoids);
        code = ellipsoids ? fc_pipeline_frame_ellipsoids(p, &p->frame, ellipsoids, err)
                          : fc_error_set(err, FC_ERR_NOMEM, "cannot allocate the ellipsoids");
    }
    fc_surface_mesh mesh = {0};
    if (code == FC_OK)
        code = fc_surface_mesher_run(passes, &p->frame, ellipsoids, settings, &mesh, err);
    if (code == FC_OK)
        code = fc_surface_raster_keep(&p->raster, p, &mesh, p->uploads, settings, err);
    fc_surface_mesh_free(&mesh);
    free(ellipsoids);
    return code;
}

static fc_settings resolve_radius(fc_pipeline *p, const fc_settings *settings)
{
    fc_settings resolved = *settings;
    p->particles.sized = !(settings->radius > 0.0f) && p->particles.has_radii;
    if (p->particles.sized)
        resolved.radius = p->particles.radius_median;
    if (settings->surface == FC_SURFACE_MODE_MESH)
        resolved.smoothing = FC_SMOOTHING_NONE;   /* the mesh is smooth already: its depth goes on as it is */
    return resolved;
}

fc_code fc_pipeline_render_with(fc_pipeline *p, const fc_camera *camera, const fc_settings *requested,
                                const fc_render_scene *scene_in, fc_aov aov, int want_u8, fc_image *out,
                                float *stage_ms, fc_error *err)
{
    const fc_render_scene scene = scene_in ? *scene_in : (fc_render_scene){0};
    if (!p || !camera || !requested || !out || (scene.mesh_count > 0 && !scene.meshes))
        return fc_error_set(err, FC_ERR_USAGE, "fc_pipeline_render: missing pipeline, camera, settings or image");
    fc_stage_timer_reset(&p->timer);
    fc_pass_profile_reset(&p->profile);
    report_stages(&p->timer, stage_ms);
    fc_code code = check_request(p, camera, requested, aov, err);
    if (code == FC_OK && requested->surface == FC_SURFACE_MODE_MESH)
        code = prepare_surface_mesh(p, requested, err);
    fc_settings resolved = resolve_radius(p, requested);
    const fc_settings *settings = &resolved;
    if (code == FC_OK)
        code = order_for(p, settings, err);
    if (code == FC_OK)
        code = shape_particles(p, settings, err);
    if (code == FC_OK)
        code = color_particles(p, settings, aov, err);
    if (code == FC_OK)
        code = foam_for(p, settings, aov, err);
    if (code != FC_OK)
        return code;
    /* The frame's amplitudes were given after the upload, or are calm. */
    fc_particle_attributes_settle(&p->attributes);

    /* Near and far hold the meshes too. */
    float lo[3], hi[3];
    scene_bounds(p, &scene, lo, hi);
    fc_view view;
    float reach = fc_anisotropy_reach(&p->particles, settings->radius);
    if (settings->surface == FC_SURFACE_MODE_MESH)
        reach *= fc_surface_kernel_reach_radii(settings->surface_kernel);   /* the mesh reaches as far as the field */
    fc_view_from_camera(camera, lo, hi, reach, &view);
    render_job job;
    plan_job(p, &view, camera, settings, &scene, aov, want_u8 != 0, &job);
    const fc_render_target *result = NULL;
    code = render_stages(p, &job, aov, &result, err);
    if (code != FC_OK)
        return code;

    fc_pixel_type type = aov == FC_AOV_COLOR && want_u8 ? FC_PIXEL_U8 : FC_PIXEL_F32;
    fc_stage_timer_begin(&p->timer, FC_STAGE_READBACK);
    fc_pass_profile_begin(&p->profile, "readback");
    code = fc_readback_run(&p->readback, result, channels_of(aov), type, out, err);
    fc_pass_profile_end(&p->profile);
    fc_stage_timer_end(&p->timer, FC_STAGE_READBACK);
    if (code == FC_OK)
        report_stages(&p->timer, stage_ms);
    return code;
}

fc_code fc_pipeline_render_scene(fc_pipeline *p, const fc_camera *camera, const fc_settings *settings,
                                 const fc_scene_textures *scene, fc_aov aov, int want_u8, fc_image *out,
                                 float *stage_ms, fc_error *err)
{
    fc_render_scene with = {.textures = scene};
    return fc_pipeline_render_with(p, camera, settings, &with, aov, want_u8, out, stage_ms, err);
}

fc_code fc_pipeline_render(fc_pipeline *p, const fc_camera *camera, const fc_settings *settings, fc_aov aov,
                           int want_u8, fc_image *out, float *stage_ms, fc_error *err)
{
    return fc_pipeline_render_with(p, camera, settings, NULL, aov, want_u8, out, stage_ms, err);
}

void fc_pipeline_force_splat(fc_pipeline *p, fc_splat_method method)
{
    p->depth.method = method;
}

fc_splat_method fc_pipeline_last_splat(const fc_pipeline *p)
{
    return p->depth.last_used;
}

fc_splat_walk fc_pipeline_last_splat_walk(const fc_pipeline *p)
{
    return p->depth.compute.last_walk;
}

fc_compute_splat *fc_pipeline_compute_splat(fc_pipeline *p)
{
    return &p->depth.compute;
}

fc_shadow_pass *fc_pipeline_shadow_pass(fc_pipeline *p)
{
    return &p->shadow;
}

bool fc_pipeline_background_writes_mask(const fc_pipeline *p)
{
    return fc_background_pass_writes_mask(&p->background);
}

bool fc_pipeline_flat_constants(const fc_pipeline *p)
{
    return p->background.programs.flat_constants && p->composite.programs.flat_constants;
}

fc_particle_attributes *fc_pipeline_particle_attributes(fc_pipeline *p)
{
    return &p->attributes;
}

const fc_anisotropy *fc_pipeline_anisotropy(const fc_pipeline *p)
{
    return &p->anisotropy;
}

fc_code fc_pipeline_frame_ellipsoids(fc_pipeline *p, const fc_frame *frame, fc_ellipsoid *out, fc_error *err)
{
    fc_code code = fc_pipeline_upload(p, frame, NULL, err);
    if (code == FC_OK)
        code = fc_anisotropy_update(&p->anisotropy, &p->particles, neighbourhood_support(p), err);
    if (code == FC_OK)
        code = fc_anisotropy_read(&p->anisotropy, frame->count, out, err);
    return code;
}

fc_code fc_pipeline_surface_passes(fc_pipeline *p, const fc_surface_passes **out, fc_error *err)
{
    if (!p->surface_built) {
        fc_code code = fc_surface_passes_create(p->shader_dir, &p->surface, err);
        if (code != FC_OK)
            return code;
        p->surface_built = true;
    }
    *out = &p->surface;
    return FC_OK;
}

void fc_pipeline_set_profiling(fc_pipeline *p, int on)
{
    p->profile.enabled = on != 0;
    fc_pass_profile_reset(&p->profile);
}

int fc_pipeline_pass_profile(const fc_pipeline *p, const fc_pass_sample **samples)
{
    *samples = p->profile.samples;
    return p->profile.enabled ? p->profile.count : 0;
}

void fc_pipeline_trim(fc_pipeline *p)
{
    fc_depth_pass_trim(&p->depth);
    fc_thickness_pass_trim(&p->thickness);
    fc_shadow_pass_trim(&p->shadow);
    fc_smoother_trim(&p->smoother);
    fc_render_target_release(&p->noise.target);
    fc_render_target_release(&p->normal.target);
    fc_render_target_release(&p->background.target);
    fc_mesh_pass_trim(&p->mesh);
    fc_render_target_release(&p->composite.srgb_target);
    fc_render_target_release(&p->composite.float_target);
}

void fc_pipeline_gpu_memory(const fc_pipeline *p, fc_gpu_memory *out)
{
    *out = (fc_gpu_memory){0};
    fc_particle_buffer_tally(&p->particles, out);
    fc_particle_attributes_tally(&p->attributes, out);
    fc_color_values_tally(&p->color_values, out);
    fc_anisotropy_tally(&p->anisotropy, out);
    fc_depth_pass_tally(&p->depth, out);
    fc_thickness_pass_tally(&p->thickness, out);
    fc_shadow_pass_tally(&p->shadow, out);
    fc_smoother_tally(&p->smoother, out);
    fc_render_target_tally(&p->noise.target, out);
    fc_render_target_tally(&p->normal.target, out);
    fc_render_target_tally(&p->background.target, out);
    fc_mesh_pass_tally(&p->mesh, out);
    fc_render_target_tally(&p->composite.srgb_target, out);
    fc_render_target_tally(&p->composite.float_target, out);
    fc_render_target_tally(&p->raster.target, out);
    fc_readback_tally(&p->readback, out);
}
