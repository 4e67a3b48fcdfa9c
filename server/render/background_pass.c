/* background_pass.c — the scene behind the fluid. */
#include "background_pass.h"

#include "fc_error.h"
#include "gl_util.h"
#include "shader_program.h"
#include "shader_variants.h"

/* Locations and units fixed by layout() in background.frag.glsl and fluid_pixel.frag.glsl. */
enum { LOC_FLOOR_PLANE = 16, LOC_DEPTH_PROJECTION = 17, LOC_USE_CLIENT_IMAGE = 30, LOC_IMAGE_SCALE = 31 };
enum { UNIT_CLIENT_IMAGE = 0 };

static const char *const program_files[] = {"fullscreen.vert.glsl", "camera.frag.glsl", "environment.frag.glsl",
                                            "fluid_pixel.frag.glsl", "background.frag.glsl"};

fc_code fc_background_pass_create(const char *shader_dir, fc_background_pass *pass, fc_error *err)
{
    *pass = (fc_background_pass){.target = fc_render_target_init(GL_RGBA16F, false, true)};
    glCreateVertexArrays(1, &pass->empty_vertex_array);
    glCreateFramebuffers(1, &pass->framebuffer);
    const GLenum outputs[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(pass->framebuffer, 2, outputs);
    /* The default look's variant now; others on first use. */
    return fc_program_variants_create(&pass->programs, shader_dir, program_files,
                                      sizeof program_files / sizeof program_files[0],
                                      FC_FEATURE_FLOOR | FC_FEATURE_SHADOW, err);
}

void fc_background_pass_destroy(fc_background_pass *pass)
{
    fc_program_variants_destroy(&pass->programs);
    glDeleteVertexArrays(1, &pass->empty_vertex_array);
    glDeleteFramebuffers(1, &pass->framebuffer);
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

fc_code fc_background_pass_run(fc_background_pass *pass, const fc_view *view, const fc_environment *env,
                               const fc_scene_textures *scene, const fc_render_target *composite, fc_error *err)
{
    unsigned features = fc_environment_features(env) | (uses_client_image(scene) ? FC_FEATURE_CLIENT_IMAGE : 0u);
    const fc_program_variant *program = NULL;
    fc_code code = fc_program_variants_get(&pass->programs, features, &program, err);
    if (code == FC_OK)
        code = fc_render_target_resize(&pass->target, view->width, view->height, err);
    if (code == FC_OK)
        code = bind_outputs(pass, composite, view, err);
    if (code != FC_OK)
        return code;
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_ALWAYS);
    glDepthMask(GL_TRUE);
    glDisable(GL_STENCIL_TEST);
    glDisable(GL_BLEND);
    /* Only an sRGB composite target encodes: the background texture is linear RGBA16F. */
    glEnable(GL_FRAMEBUFFER_SRGB);
    glUseProgram(program->program);
    fc_environment_apply_to(env, view, program->uniforms);
    apply_client_image(scene, view, program->uniforms);
    if (fc_uniform_active(program->uniforms, LOC_FLOOR_PLANE))
        glUniform4fv(LOC_FLOOR_PLANE, 1, env->floor_plane);
    if (fc_uniform_active(program->uniforms, LOC_DEPTH_PROJECTION))
        glUniform2f(LOC_DEPTH_PROJECTION, view->p22, view->p32);
    fc_gl_draw_fullscreen(pass->empty_vertex_array);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glDisable(GL_DEPTH_TEST);
    return fc_gl_check("background pass", err);
}
