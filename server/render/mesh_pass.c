/* mesh_pass.c — see mesh_pass.h. */
#include "mesh_pass.h"

#include <math.h>

#include "fc_error.h"
#include "gl_util.h"
#include "mesh_buffers.h"
#include "shader_program.h"

/* Uniform locations fixed by layout(location) in mesh.vert.glsl, mesh_shade.frag.glsl and mesh_occlusion.comp.glsl. */
enum {
    LOC_MESH_TO_VIEW = 60,
    LOC_NORMAL_TO_VIEW = 64,
    LOC_PROJECTION = 67,
    LOC_HAS_NORMALS = 68,
    LOC_ALBEDO = 69,
    LOC_OPACITY = 70,
    LOC_OCCLUSION_SIZE = 0
};
enum { IMAGE_FLUID_DEPTH = 0, UNIT_MESH_DEPTH = 1 };
#define OCCLUSION_TILE 8
/* Texels per side of the meshes' shadow map: walls and obstacles cast
 * sharp-edged shadows, unlike the fluid's soft one (256, shadow_pass.c). */
#define SUN_MAP_SIZE 1024u
/* How far behind its own depth in that map a surface may lie and still be lit, in map texels. */
#define SHADOW_BIAS_TEXELS 3.0f

/* Which meshes a draw takes. */
typedef enum mesh_kind { OPAQUE_ALL, OPAQUE_CASTERS, GLASS } mesh_kind;

fc_code fc_mesh_pass_create(const char *shader_dir, fc_mesh_pass *pass, fc_error *err)
{
    *pass = (fc_mesh_pass){.depth = fc_render_target_init(GL_R32F, true, false),
                           .sun_depth = fc_render_target_init(GL_R32F, true, true)};
    glCreateFramebuffers(1, &pass->shade_framebuffer);
    const char *depth[] = {"mesh.vert.glsl", "mesh_depth.frag.glsl"};
    const char *shade[] = {"mesh.vert.glsl", "camera.frag.glsl", "environment.frag.glsl", "mesh_shade.frag.glsl"};
    const char *occlusion[] = {"mesh_occlusion.comp.glsl"};
    fc_code code = fc_program_build(shader_dir, depth, 2, &pass->depth_program, err);
    if (code == FC_OK)
        code = fc_program_build(shader_dir, shade, 4, &pass->shade_program, err);
    if (code == FC_OK)
        code = fc_program_build(shader_dir, occlusion, 1, &pass->occlusion_program, err);
    return code;
}

void fc_mesh_pass_destroy(fc_mesh_pass *pass)
{
    glDeleteProgram(pass->depth_program);
    glDeleteProgram(pass->shade_program);
    glDeleteProgram(pass->occlusion_program);
    glDeleteFramebuffers(1, &pass->shade_framebuffer);
    fc_render_target_release(&pass->depth);
    fc_render_target_release(&pass->sun_depth);
    pass->depth_program = pass->shade_program = pass->occlusion_program = pass->shade_framebuffer = 0;
}

static bool is_opaque(const fc_scene_mesh *m)
{
    return m->opacity >= 1.0f;
}

static bool takes(mesh_kind kind, const fc_scene_mesh *m)
{
    switch (kind) {
    case OPAQUE_ALL: return is_opaque(m);
    case OPAQUE_CASTERS: return is_opaque(m) && !m->hide_near;
    case GLASS: return !is_opaque(m) && m->opacity > 0.0f;
    }
    return false;
}

bool fc_mesh_any_opaque(const fc_scene_mesh *meshes, uint32_t count)
{
    for (uint32_t i = 0; i < count; i++)
        if (is_opaque(&meshes[i]))
            return true;
    return false;
}

/* x' = M x with M 3x4 row-major. */
static void place_point(const float m[12], const float x[3], float out[3])
{
    for (int r = 0; r < 3; r++)
        out[r] = m[4 * r] * x[0] + m[4 * r + 1] * x[1] + m[4 * r + 2] * x[2] + m[4 * r + 3];
}

void fc_mesh_bounds(const fc_scene_mesh *meshes, uint32_t count, float lo[3], float hi[3])
{
    for (uint32_t i = 0; i < count; i++) {
        const fc_mesh_buffers *b = meshes[i].buffers;
        for (int corner = 0; corner < 8; corner++) {
            float x[3] = {corner & 1 ? b->hi[0] : b->lo[0], corner & 2 ? b->hi[1] : b->lo[1],
                          corner & 4 ? b->hi[2] : b->lo[2]};
            float w[3];
            place_point(meshes[i].transform, x, w);
            for (int k = 0; k < 3; k++) {
                lo[k] = fminf(lo[k], w[k]);
                hi[k] = fmaxf(hi[k], w[k]);
            }
        }
    }
}

/* view (column-major 4x4) times the mesh's transform: column-major 4x4. */
static void mesh_to_view(const fc_view *view, const float m[12], float out[16])
{
    float model[16] = {0};
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 3; r++)
            model[4 * c + r] = m[4 * r + c];
    model[15] = 1.0f;
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++) {
            float sum = 0.0f;
            for (int k = 0; k < 4; k++)
                sum += view->view[4 * k + r] * model[4 * c + k];
            out[4 * c + r] = sum;
        }
}

/* The inverse transpose of the upper 3x3 of a column-major 4x4, column-major;
 * the matrix itself when it is singular (normals then only need a direction). */
static void normal_matrix(const float a[16], float out[9])
{
    float m[3][3];   /* m[r][c] */
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++)
            m[r][c] = a[4 * c + r];
    float cof[3][3];
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++)
            cof[r][c] = m[(r + 1) % 3][(c + 1) % 3] * m[(r + 2) % 3][(c + 2) % 3] -
                        m[(r + 1) % 3][(c + 2) % 3] * m[(r + 2) % 3][(c + 1) % 3];
    float det = m[0][0] * cof[0][0] + m[0][1] * cof[0][1] + m[0][2] * cof[0][2];
    bool singular = !(fabsf(det) > 1e-30f);
    /* inverse transpose = cofactor matrix / det */
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++)
            out[3 * c + r] = singular ? m[r][c] : cof[r][c] / det;
}

/* Draws the meshes of `kind` with `program` through `view`; cull selects
 * which faces of a mesh without hide_near go (GL_NONE: both). */
static void draw_meshes(GLuint program, bool shading, const fc_scene_mesh *meshes, uint32_t count,
                        const fc_view *view, mesh_kind kind, GLenum cull, bool camera)
{
    glUseProgram(program);
    glProgramUniform4f(program, LOC_PROJECTION, view->fx, view->fy, view->p22, view->p32);
    for (uint32_t i = 0; i < count; i++) {
        const fc_scene_mesh *m = &meshes[i];
        /* A tank's near faces are culled for the camera: of its glass only the far faces go. */
        if (!takes(kind, m) || (camera && m->hide_near && cull == GL_BACK))
            continue;
        float to_view[16], normals[9];
        mesh_to_view(view, m->transform, to_view);
        normal_matrix(to_view, normals);
        glProgramUniformMatrix4fv(program, LOC_MESH_TO_VIEW, 1, GL_FALSE, to_view);
        /* The depth program has no shading uniforms (setting one would be an error). */
        if (shading) {
            glProgramUniformMatrix3fv(program, LOC_NORMAL_TO_VIEW, 1, GL_FALSE, normals);
            glProgramUniform1i(program, LOC_HAS_NORMALS, m->buffers->normals != 0);
            glProgramUniform3fv(program, LOC_ALBEDO, 1, m->color);
            glProgramUniform1f(program, LOC_OPACITY, m->opacity);
        }
        /* The camera's near faces of a tank go; the sun sees whole meshes. */
        GLenum face = camera && m->hide_near ? GL_FRONT : cull;
        if (face == GL_NONE) {
            glDisable(GL_CULL_FACE);
        } else {
            glEnable(GL_CULL_FACE);
            glCullFace(face);
        }
        glBindVertexArray(m->buffers->vertex_array);
        glDrawElements(GL_TRIANGLES, m->buffers->index_count, GL_UNSIGNED_INT, NULL);
    }
    glDisable(GL_CULL_FACE);
    glBindVertexArray(0);
}

/* The nearest surface's linear depth into `target` (cleared to `none`). */
static fc_code render_depth(fc_mesh_pass *pass, fc_render_target *target, const fc_scene_mesh *meshes,
                            uint32_t count, const fc_view *view, uint32_t width, uint32_t height, mesh_kind kind,
                            float none, bool camera, fc_error *err)
{
    fc_code code = fc_render_target_resize(target, width, height, err);
    if (code != FC_OK)
        return code;
    fc_render_target_bind(target);
    glClearNamedFramebufferfv(target->framebuffer, GL_COLOR, 0, &none);
    glClearNamedFramebufferfi(target->framebuffer, GL_DEPTH_STENCIL, 0, 1.0f, 0);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glDisable(GL_FRAMEBUFFER_SRGB);
    draw_meshes(pass->depth_program, false, meshes, count, view, kind, GL_NONE, camera);
    glDisable(GL_DEPTH_TEST);
    return fc_gl_check("mesh depth", err);
}

fc_code fc_mesh_pass_occlude(fc_mesh_pass *pass, const fc_scene_mesh *meshes, uint32_t count, const fc_view *view,
                             const fc_render_target *fluid_depth, fc_error *err)
{
    if (!fc_mesh_any_opaque(meshes, count))
        return FC_OK;
    fc_code code = render_depth(pass, &pass->depth, meshes, count, view, view->width, view->height, OPAQUE_ALL, 0.0f,
                                true, err);
    if (code != FC_OK)
        return code;
    glUseProgram(pass->occlusion_program);
    glProgramUniform2i(pass->occlusion_program, LOC_OCCLUSION_SIZE, (GLint)view->width, (GLint)view->height);
    glBindImageTexture(IMAGE_FLUID_DEPTH, fluid_depth->color, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32F);
    glBindTextureUnit(UNIT_MESH_DEPTH, pass->depth.color);
    glDispatchCompute((view->width + OCCLUSION_TILE - 1) / OCCLUSION_TILE,
                      (view->height + OCCLUSION_TILE - 1) / OCCLUSION_TILE, 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
    return fc_gl_check("mesh occlusion", err);
}

fc_code fc_mesh_pass_cast_shadows(fc_mesh_pass *pass, const fc_scene_mesh *meshes, uint32_t count,
                                  const fc_view *sun_view, fc_environment *env, fc_error *err)
{
    bool casts = false;
    for (uint32_t i = 0; i < count; i++)
        casts |= takes(OPAQUE_CASTERS, &meshes[i]);
    if (!casts || !env->has_shadow)
        return FC_OK;
    fc_code code = render_depth(pass, &pass->sun_depth, meshes, count, sun_view, SUN_MAP_SIZE, SUN_MAP_SIZE,
                                OPAQUE_CASTERS, INFINITY, false, err);
    if (code != FC_OK)
        return code;
    /* A map texel at the box's distance from the sun, 2 d / (f size) in world units. */
    float distance = 0.5f * (sun_view->near_plane + sun_view->far_plane);
    env->mesh_shadow_bias = SHADOW_BIAS_TEXELS * 2.0f * distance / (sun_view->fy * (float)SUN_MAP_SIZE);
    env->has_mesh_shadow = true;
    env->mesh_sun_depth = pass->sun_depth.color;
    env->mesh_sun_depth_uv_scale[0] = (float)pass->sun_depth.width / (float)pass->sun_depth.texture_width;
    env->mesh_sun_depth_uv_scale[1] = (float)pass->sun_depth.height / (float)pass->sun_depth.texture_height;
    return FC_OK;
}

/* The shading program's framebuffer: attachment 0 the scene radiance (or
 * none), 1 the image's colour, with the image's depth. */
static fc_code bind_shading(fc_mesh_pass *pass, const fc_render_target *background, const fc_render_target *image,
                            const fc_view *view, fc_error *err)
{
    glNamedFramebufferTexture(pass->shade_framebuffer, GL_COLOR_ATTACHMENT0, background ? background->color : 0, 0);
    glNamedFramebufferTexture(pass->shade_framebuffer, GL_COLOR_ATTACHMENT1, image->color, 0);
    glNamedFramebufferRenderbuffer(pass->shade_framebuffer, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, image->depth);
    const GLenum outputs[] = {background ? GL_COLOR_ATTACHMENT0 : GL_NONE, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(pass->shade_framebuffer, 2, outputs);
    if (glCheckNamedFramebufferStatus(pass->shade_framebuffer, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        return fc_error_set(err, FC_ERR_GL, "mesh pass: framebuffer incomplete");
    glBindFramebuffer(GL_FRAMEBUFFER, pass->shade_framebuffer);
    glViewport(0, 0, (GLsizei)view->width, (GLsizei)view->height);
    return FC_OK;
}

static void begin_shading(const fc_mesh_pass *pass, const fc_view *view, const fc_environment *env, bool want_u8)
{
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDisable(GL_STENCIL_TEST);
    /* Only an sRGB image encodes: the background texture is linear RGBA16F. */
    if (want_u8)
        glEnable(GL_FRAMEBUFFER_SRGB);
    else
        glDisable(GL_FRAMEBUFFER_SRGB);
    glUseProgram(pass->shade_program);
    fc_environment_apply(env, view);
}

static fc_code end_shading(const char *what, fc_error *err)
{
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_FRAMEBUFFER_SRGB);
    glDepthMask(GL_TRUE);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return fc_gl_check(what, err);
}

fc_code fc_mesh_pass_draw_opaque(fc_mesh_pass *pass, const fc_scene_mesh *meshes, uint32_t count,
                                 const fc_view *view, const fc_environment *env, const fc_render_target *background,
                                 const fc_render_target *image, bool want_u8, fc_error *err)
{
    if (!fc_mesh_any_opaque(meshes, count))
        return FC_OK;
    fc_code code = bind_shading(pass, background, image, view, err);
    if (code != FC_OK)
        return code;
    begin_shading(pass, view, env, want_u8);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    draw_meshes(pass->shade_program, true, meshes, count, view, OPAQUE_ALL, GL_NONE, true);
    return end_shading("drawing opaque meshes", err);
}

fc_code fc_mesh_pass_draw_glass(fc_mesh_pass *pass, const fc_scene_mesh *meshes, uint32_t count, const fc_view *view,
                                const fc_environment *env, const fc_render_target *image, bool want_u8,
                                fc_error *err)
{
    bool any = false;
    for (uint32_t i = 0; i < count; i++)
        any |= takes(GLASS, &meshes[i]);
    if (!any)
        return FC_OK;
    fc_code code = bind_shading(pass, NULL, image, view, err);
    if (code != FC_OK)
        return code;
    begin_shading(pass, view, env, want_u8);
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
    /* Far faces first, then near ones over them: a closed glass body reads
     * right from any side without sorting its triangles. */
    draw_meshes(pass->shade_program, true, meshes, count, view, GLASS, GL_FRONT, true);
    draw_meshes(pass->shade_program, true, meshes, count, view, GLASS, GL_BACK, true);
    glBlendFunc(GL_ONE, GL_ONE);
    return end_shading("drawing glass meshes", err);
}

void fc_mesh_pass_tally(const fc_mesh_pass *pass, fc_gpu_memory *m)
{
    fc_render_target_tally(&pass->depth, m);
    fc_render_target_tally(&pass->sun_depth, m);
}

void fc_mesh_pass_trim(fc_mesh_pass *pass)
{
    fc_render_target_release(&pass->depth);
    fc_render_target_release(&pass->sun_depth);
}
