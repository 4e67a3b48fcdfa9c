/* render_target.c — framebuffers with a colour texture and optional depth. */
#include "render_target.h"

#include "fc_error.h"
#include "gl_util.h"

fc_render_target fc_render_target_init(GLenum color_format, bool with_depth, bool linear)
{
    return (fc_render_target){.color_format = color_format, .with_depth = with_depth, .linear = linear};
}

static void delete_attachments(fc_render_target *t)
{
    glDeleteFramebuffers(1, &t->framebuffer);
    glDeleteTextures(1, &t->color);
    glDeleteRenderbuffers(1, &t->depth);
    t->framebuffer = t->color = t->depth = 0;
    t->width = t->height = 0;
    t->texture_width = t->texture_height = 0;
    t->bytes = 0;
}

static fc_code attach_depth(fc_render_target *t, fc_error *err)
{
    glCreateRenderbuffers(1, &t->depth);
    glNamedRenderbufferStorage(t->depth, GL_DEPTH32F_STENCIL8, (GLsizei)t->texture_width,
                               (GLsizei)t->texture_height);
    glNamedFramebufferRenderbuffer(t->framebuffer, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER, t->depth);
    return fc_gl_check("allocating a depth buffer", err);
}

static uint64_t attachment_bytes(const fc_render_target *t)
{
    uint64_t per_pixel = fc_gl_texel_bytes(t->color_format);
    if (t->with_depth)
        per_pixel += fc_gl_texel_bytes(GL_DEPTH32F_STENCIL8);
    return per_pixel * t->texture_width * t->texture_height;
}

static fc_code allocate(fc_render_target *t, fc_error *err)
{
    t->allocations++;
    fc_code code =
        fc_gl_texture_create(t->color_format, t->texture_width, t->texture_height, t->linear, &t->color, err);
    if (code != FC_OK)
        return code;
    glCreateFramebuffers(1, &t->framebuffer);
    glNamedFramebufferTexture(t->framebuffer, GL_COLOR_ATTACHMENT0, t->color, 0);
    if (t->with_depth && (code = attach_depth(t, err)) != FC_OK)
        return code;
    GLenum status = glCheckNamedFramebufferStatus(t->framebuffer, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
        return fc_error_set(err, FC_ERR_GL, "render target %ux%u (format 0x%04x) incomplete: status 0x%04x",
                            t->texture_width, t->texture_height, (unsigned)t->color_format, (unsigned)status);
    return fc_gl_check("allocating a render target", err);
}

fc_code fc_render_target_resize(fc_render_target *t, uint32_t width, uint32_t height, fc_error *err)
{
    if (!t->framebuffer || width > t->texture_width || height > t->texture_height) {
        uint32_t grown_width = fc_gl_grown_extent(width, t->texture_width);
        uint32_t grown_height = fc_gl_grown_extent(height, t->texture_height);
        delete_attachments(t);
        t->texture_width = grown_width;
        t->texture_height = grown_height;
        fc_code code = allocate(t, err);
        if (code != FC_OK) {
            delete_attachments(t);
            return code;
        }
        t->bytes = attachment_bytes(t);
    }
    t->width = width;
    t->height = height;
    return FC_OK;
}

void fc_render_target_bind(const fc_render_target *t)
{
    glBindFramebuffer(GL_FRAMEBUFFER, t->framebuffer);
    glViewport(0, 0, (GLsizei)t->width, (GLsizei)t->height);
}

void fc_render_target_bind_overlay(const fc_render_target *t)
{
    fc_render_target_bind(t);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_FALSE);
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
    if (t->color_format == GL_SRGB8_ALPHA8)
        glEnable(GL_FRAMEBUFFER_SRGB);
}

void fc_render_target_release(fc_render_target *t)
{
    delete_attachments(t);
}

void fc_render_target_uniform_size(GLuint program, GLint location, const fc_render_target *t)
{
    glProgramUniform2i(program, location, (GLint)t->width, (GLint)t->height);
}

void fc_render_target_tally(const fc_render_target *t, fc_gpu_memory *m)
{
    m->render_target_bytes += t->bytes;
    m->allocations += t->allocations;
}
