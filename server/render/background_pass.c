/* background_pass.c — the scene behind the fluid. */
#include "background_pass.h"

#include "background_regions.h"

#include "fc_error.h"
#include "gl_util.h"
#include "shader_program.h"
#include "shader_variants.h"

/* Locations and units fixed by layout() in background.frag.glsl, fluid_pixel.frag.glsl and fullscreen_clip.vert.glsl. */
enum { LOC_FLOOR_PLANE = 16, LOC_DEPTH_PROJECTION = 17, LOC_USE_CLIENT_IMAGE = 30, LOC_IMAGE_SCALE = 31,
       LOC_DEPTH_TEXEL_UV = 54, LOC_CLIP_PLANES = 56 };
enum { UNIT_SURFACE_DEPTH = 0, UNIT_CLIENT_IMAGE = 8 };

static const char *const program_files[] = {"fullscreen_clip.vert.glsl", "camera.frag.glsl",
                                            "environment.frag.glsl", "fluid_pixel.frag.glsl", "background.frag.glsl"};
/* The default look's variants (background_regions.h): sky, band, floor with and without the shadow. */
static const unsigned default_features[] = {
    0u, FC_FEATURE_FLOOR | FC_FEATURE_SHADOW, FC_FEATURE_FLOOR | FC_FEATURE_SHADOW | FC_FEATURE_FLOOR_ONLY,
    FC_FEATURE_FLOOR | FC_FEATURE_FLOOR_ONLY};

fc_code fc_background_pass_create(const char *shader_dir, bool flat_constants, fc_background_pass *pass,
                                  fc_error *err)
{
    *pass = (fc_background_pass){.target = fc_render_target_init(GL_RGBA16F, false, true)};
    glCreateVertexArrays(1, &pass->empty_vertex_array);
    glCreateFramebuffers(1, &pass->framebuffer);
    pass->depth_sampler = fc_gl_nearest_sampler();
    const GLenum outputs[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(pass->framebuffer, 2, outputs);
    pass->writes_mask = epoxy_has_gl_extension("GL_ARB_shader_stencil_export");
    /* The default look's variants now; others on first use. */
    unsigned mask = pass->writes_mask ? FC_FEATURE_FLUID_MASK : 0u;
    const fc_program_options options = {.shader_dir = shader_dir, .flat_constants = flat_constants};
    fc_code code = fc_program_variants_create(&pass->programs, &options, program_files,
                                              sizeof program_files / sizeof program_files[0],
                                              default_features[0] | mask, err);
    for (size_t i = 1; i < sizeof default_features / sizeof default_features[0] && code == FC_OK; i++) {
        const fc_program_variant *v = NULL;
        code = fc_program_variants_get(&pass->programs, default_features[i] | mask, &v, err);
    }
    return code;
}

void fc_background_pass_destroy(fc_background_pass *pass)
{
    fc_program_variants_destroy(&pass->programs);
    glDeleteVertexArrays(1, &pass->empty_vertex_array);
    glDeleteFramebuffers(1, &pass->framebuffer);
    glDeleteSamplers(1, &pass->depth_sampler);
    pass->depth_sampler = 0;
    fc_render_target_release(&pass->target);
    pass->empty_vertex_array = pass->framebuffer = 0;
}

/* The part of the image's uv square the view shows: all of one axis, the
 * centre of the other, so the image covers the view without distortion. */
static bool uses_client_image(const fc_scene_textures *scene)
{
    return scene && scene->background;
}

static void apply_client_image(const fc_scene_textures *scene, const fc_view *view, uint64_t uniforms)
{
    bool use = uses_client_image(scene);
    if (fc_uniform_active(uniforms, LOC_USE_CLIENT_IMAGE))
        glUniform1i(LOC_USE_CLIENT_IMAGE, use);
    if (!use)
        return;
    float view_aspect = (float)view->width / (float)view->height;
    float ratio = view_aspect / scene->background_aspect;
    if (fc_uniform_active(uniforms, LOC_IMAGE_SCALE))
        glUniform2f(LOC_IMAGE_SCALE, ratio < 1.0f ? ratio : 1.0f, ratio < 1.0f ? 1.0f : 1.0f / ratio);
    glBindTextureUnit(UNIT_CLIENT_IMAGE, scene->background);
}

/* The background texture and the composite's colour and depth as one
 * framebuffer; attachments of different sizes are fine, the view fits both. */
static fc_code bind_outputs(const fc_background_pass *pass, const fc_render_target *composite, const fc_view *view,
                            fc_error *err)
{
    glNamedFramebufferTexture(pass->framebuffer, GL_COLOR_ATTACHMENT0, pass->target.color, 0);
    glNamedFramebufferTexture(pass->framebuffer, GL_COLOR_ATTACHMENT1, composite->color, 0);
    glNamedFramebufferRenderbuffer(pass->framebuffer, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, composite->depth);
    if (glCheckNamedFramebufferStatus(pass->framebuffer, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return fc_error_set(err, FC_ERR_GL, "background pass: framebuffer incomplete");
    glBindFramebuffer(GL_FRAMEBUFFER, pass->framebuffer);
    glViewport(0, 0, (GLsizei)view->width, (GLsizei)view->height);
    return FC_OK;
}

/* One region of the image with its variant. */
static fc_code draw_region(fc_background_pass *pass, const fc_background_draw *draw, const fc_view *view,
                           const fc_environment *env, const fc_scene_textures *scene, const float depth_texel_uv[2],
                           fc_error *err)
{
    const fc_program_variant *program = NULL;
    fc_code code = fc_program_variants_get(&pass->programs, draw->features, &program, err);
    if (code != FC_OK)
        return code;
    uint64_t uniforms = program->uniforms;
    glUseProgram(program->program);
    fc_environment_apply_to(env, view, uniforms);
    apply_client_image(scene, view, uniforms);
    if (fc_uniform_active(uniforms, LOC_FLOOR_PLANE))
        glUniform4fv(LOC_FLOOR_PLANE, 1, env->floor_plane);
    if (fc_uniform_active(uniforms, LOC_DEPTH_PROJECTION))
        glUniform2f(LOC_DEPTH_PROJECTION, view->p22, view->p32);
    if (fc_uniform_active(uniforms, LOC_DEPTH_TEXEL_UV))
        glUniform2fv(LOC_DEPTH_TEXEL_UV, 1, depth_texel_uv);
    if (fc_uniform_active(uniforms, LOC_CLIP_PLANES))
        glUniform3fv(LOC_CLIP_PLANES, 2, &draw->clip_planes[0][0]);
    if (draw->scissored) {
        glEnable(GL_SCISSOR_TEST);
        glScissor(draw->scissor[0], draw->scissor[1], draw->scissor[2], draw->scissor[3]);
    }
    fc_gl_draw_fullscreen(pass->empty_vertex_array);
    glDisable(GL_SCISSOR_TEST);
    return FC_OK;
}

bool fc_background_pass_writes_mask(const fc_background_pass *pass)
{
    return pass->writes_mask;
}

/* The composite's mask (composite_pass.c) laid down with the background:
 * every pixel passes the depth test and takes the stencil its fragment
 * exports, 1 on the fluid. */
static void begin_mask(const fc_background_pass *pass, const fc_render_target *fluid_depth)
{
    glBindTextureUnit(UNIT_SURFACE_DEPTH, fluid_depth->color);
    glBindSampler(UNIT_SURFACE_DEPTH, pass->depth_sampler);
    glEnable(GL_STENCIL_TEST);
    glStencilMask(0xff);
    glStencilFunc(GL_ALWAYS, 0, 0xff);
    glStencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
}

fc_code fc_background_pass_run(fc_background_pass *pass, const fc_view *view, const fc_environment *env,
                               const fc_scene_textures *scene, const fc_render_target *fluid_depth,
                               const fc_render_target *composite, fc_error *err)
{
    unsigned features = fc_environment_features(env) | (uses_client_image(scene) ? FC_FEATURE_CLIENT_IMAGE : 0u);
    if (fluid_depth && !pass->writes_mask)
        return fc_error_set(err, FC_ERR_GL, "background pass: the driver cannot write the fluid's mask");
    if (fluid_depth)
        features |= FC_FEATURE_FLUID_MASK;
    fc_background_draw draws[FC_BACKGROUND_DRAWS_MAX];
    int count = fc_background_regions(view, env, features, draws);
    fc_code code = fc_render_target_resize(&pass->target, view->width, view->height, err);
    if (code == FC_OK)
        code = bind_outputs(pass, composite, view, err);
    if (code != FC_OK)
        return code;
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_ALWAYS);
    glDepthMask(GL_TRUE);
    glDisable(GL_STENCIL_TEST);
    float depth_texel_uv[2] = {0.0f, 0.0f};
    if (fluid_depth) {
        begin_mask(pass, fluid_depth);
        depth_texel_uv[0] = 1.0f / (float)fluid_depth->texture_width;
        depth_texel_uv[1] = 1.0f / (float)fluid_depth->texture_height;
    }
    glDisable(GL_BLEND);
    glEnable(GL_CLIP_DISTANCE0);
    glEnable(GL_CLIP_DISTANCE1);
    /* Only an sRGB composite target encodes: the background texture is linear RGBA16F. */
    glEnable(GL_FRAMEBUFFER_SRGB);
    for (int i = 0; i < count && code == FC_OK; i++)
        code = draw_region(pass, &draws[i], view, env, scene, depth_texel_uv, err);
    glDisable(GL_CLIP_DISTANCE0);
    glDisable(GL_CLIP_DISTANCE1);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_STENCIL_TEST);
    glBindSampler(UNIT_SURFACE_DEPTH, 0);
    if (code != FC_OK)
        return code;
    return fc_gl_check("background pass", err);
}
