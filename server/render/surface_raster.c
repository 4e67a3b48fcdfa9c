/* surface_raster.c — the surface mesh's depth (surface_raster.h), drawn
 * with the scene meshes' depth program (mesh.vert.glsl, mesh_depth.frag.glsl):
 * the mesh is in world space, so its transform is the view's. */
#include "surface_raster.h"

#include <string.h>

#include "fc_error.h"
#include "gl_util.h"
#include "shader_program.h"

/* Uniform locations of mesh.vert.glsl. */
enum { LOC_MESH_TO_VIEW = 60, LOC_PROJECTION = 67 };

fc_code fc_surface_raster_create(const char *shader_dir, fc_surface_raster *r, fc_error *err)
{
    memset(r, 0, sizeof *r);
    r->target = fc_render_target_init(GL_R32F, true, false);
    const char *depth[] = {"mesh.vert.glsl", "mesh_depth.frag.glsl"};
    const char *thickness[] = {"mesh.vert.glsl", "surface_thickness.frag.glsl"};
    fc_code code = fc_program_build(shader_dir, depth, 2, &r->depth_program, err);
    return code == FC_OK ? fc_program_build(shader_dir, thickness, 2, &r->thickness_program, err) : code;
}

static void drop_mesh(fc_surface_raster *r)
{
    if (r->buffers)
        fc_mesh_buffers_destroy(r->buffers);
    r->buffers = NULL;
    r->valid = false;
}

void fc_surface_raster_destroy(fc_surface_raster *r)
{
    drop_mesh(r);
    fc_render_target_release(&r->target);
    glDeleteProgram(r->depth_program);
    glDeleteProgram(r->thickness_program);
    memset(r, 0, sizeof *r);
}

bool fc_surface_raster_holds(const fc_surface_raster *r, uint64_t upload, const fc_settings *settings)
{
    return r->valid && r->upload == upload && r->radius == settings->radius && r->cell == settings->surface_cell &&
           r->kernel == (uint32_t)settings->surface_kernel && r->smoothing == settings->surface_smoothing;
}

fc_code fc_surface_raster_keep(fc_surface_raster *r, fc_pipeline *p, const fc_surface_mesh *mesh, uint64_t upload,
                               const fc_settings *settings, fc_error *err)
{
    drop_mesh(r);
    if (mesh->triangle_count > 0) {
        fc_mesh m = {.vertex_count = mesh->vertex_count, .triangle_count = mesh->triangle_count,
                     .vertices = mesh->positions, .indices = mesh->indices, .normals = mesh->normals,
                     .opacity = 1.0f, .transform = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0}};
        fc_code code = fc_mesh_buffers_create(p, &m, &r->buffers, err);
        if (code != FC_OK)
            return code;
    }
    r->valid = true;
    r->upload = upload;
    r->radius = settings->radius;
    r->cell = settings->surface_cell;
    r->kernel = (uint32_t)settings->surface_kernel;
    r->smoothing = settings->surface_smoothing;
    return FC_OK;
}

static void draw(GLuint program, const fc_surface_raster *r, const fc_view *view)
{
    glUseProgram(program);
    glProgramUniform4f(program, LOC_PROJECTION, view->fx, view->fy, view->p22, view->p32);
    glProgramUniformMatrix4fv(program, LOC_MESH_TO_VIEW, 1, GL_FALSE, view->view);
    glBindVertexArray(r->buffers->vertex_array);
    glDrawElements(GL_TRIANGLES, r->buffers->index_count, GL_UNSIGNED_INT, NULL);
    glBindVertexArray(0);
}

fc_code fc_surface_raster_thickness(fc_surface_raster *r, const fc_view *view, fc_render_target *thickness,
                                    fc_error *err)
{
    fc_code code = fc_render_target_resize(thickness, view->width, view->height, err);
    if (code != FC_OK)
        return code;
    const float none = 0.0f;
    fc_render_target_bind(thickness);
    glClearNamedFramebufferfv(thickness->framebuffer, GL_COLOR, 0, &none);
    if (r->buffers) {
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_CULL_FACE);
        glDisable(GL_FRAMEBUFFER_SRGB);
        glEnable(GL_BLEND);
        glBlendEquation(GL_FUNC_ADD);
        glBlendFunc(GL_ONE, GL_ONE);
        draw(r->thickness_program, r, view);
        glDisable(GL_BLEND);
    }
    return fc_gl_check("surface mesh thickness", err);
}

fc_code fc_surface_raster_depth(fc_surface_raster *r, const fc_view *view, fc_render_target *depth, fc_error *err)
{
    fc_code code = fc_render_target_resize(&r->target, view->width, view->height, err);
    if (code == FC_OK)
        code = fc_render_target_resize(depth, view->width, view->height, err);
    if (code != FC_OK)
        return code;
    const float none = 0.0f;
    fc_render_target_bind(&r->target);
    glClearNamedFramebufferfv(r->target.framebuffer, GL_COLOR, 0, &none);
    glClearNamedFramebufferfi(r->target.framebuffer, GL_DEPTH_STENCIL, 0, 1.0f, 0);
    if (r->buffers) {
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        glDisable(GL_BLEND);
        glDisable(GL_CULL_FACE);
        glDisable(GL_FRAMEBUFFER_SRGB);
        draw(r->depth_program, r, view);
        glDisable(GL_DEPTH_TEST);
    }
    glCopyImageSubData(r->target.color, GL_TEXTURE_2D, 0, 0, 0, 0, depth->color, GL_TEXTURE_2D, 0, 0, 0, 0,
                       (GLsizei)view->width, (GLsizei)view->height, 1);
    return fc_gl_check("surface mesh depth", err);
}
