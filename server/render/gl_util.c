/* gl_util.c — GL error checks, waits, texture creation, draws and dispatches shared by the passes. */
#include "gl_util.h"

#include <string.h>

#include "fc_error.h"

static const char *gl_error_name(GLenum code)
{
    switch (code) {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    case GL_STACK_OVERFLOW: return "GL_STACK_OVERFLOW";
    case GL_STACK_UNDERFLOW: return "GL_STACK_UNDERFLOW";
    }
    return "unknown GL error";
}

fc_code fc_gl_check(const char *what, fc_error *err)
{
    GLenum first = glGetError();
    if (first == GL_NO_ERROR)
        return FC_OK;
    /* Several flags may be set; clear them all so the next check starts clean,
     * and let an out-of-memory anywhere decide the code. */
    int out_of_memory = first == GL_OUT_OF_MEMORY;
    for (GLenum more = glGetError(); more != GL_NO_ERROR; more = glGetError())
        out_of_memory |= more == GL_OUT_OF_MEMORY;
    if (out_of_memory)
        return fc_error_set(err, FC_ERR_RENDER, "%s: the GPU ran out of memory (GL_OUT_OF_MEMORY)", what);
    return fc_error_set(err, FC_ERR_GL, "%s: %s (0x%04x)", what, gl_error_name(first), (unsigned)first);
}

fc_code fc_gl_failure(const char *what, fc_error *err)
{
    fc_code code = fc_gl_check(what, err);
    return code != FC_OK ? code : fc_error_set(err, FC_ERR_RENDER, "%s failed", what);
}

fc_code fc_gl_wait_until_done(const char *what, fc_error *err)
{
    GLsync done = glFenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    GLenum status = glClientWaitSync(done, GL_SYNC_FLUSH_COMMANDS_BIT, GL_TIMEOUT_IGNORED);
    glDeleteSync(done);
    return status == GL_WAIT_FAILED ? fc_gl_failure(what, err) : FC_OK;
}

uint64_t fc_gl_non_pot(uint64_t n)
{
    while (n != 0 && (n & (n - 1)) == 0)   /* 1 -> 2 -> 3 */
        n++;
    return n;
}

uint32_t fc_gl_grown_extent(uint32_t asked, uint32_t allocated)
{
    return (uint32_t)fc_gl_non_pot(asked > allocated ? asked : allocated);
}

fc_code fc_gl_texture_create(GLenum internal_format, uint32_t width, uint32_t height, bool linear,
                             GLuint *texture, fc_error *err)
{
    GLuint tex = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    glTextureStorage2D(tex, 1, internal_format, (GLsizei)width, (GLsizei)height);
    GLint filter = linear ? GL_LINEAR : GL_NEAREST;
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, filter);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, filter);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(tex, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    fc_code code = fc_gl_check("creating a render texture", err);
    if (code != FC_OK) {
        glDeleteTextures(1, &tex);
        return code;
    }
    *texture = tex;
    return FC_OK;
}

uint32_t fc_gl_texel_bytes(GLenum internal_format)
{
    switch (internal_format) {
    case GL_R8UI:
        return 1;
    case GL_R32F:
    case GL_R32UI:
    case GL_SRGB8_ALPHA8:
        return 4;
    case GL_RG32F:
    case GL_RGBA16F:
    case GL_DEPTH32F_STENCIL8:   /* 32-bit float depth, 8-bit stencil and 24 unused bits */
        return 8;
    case GL_RGBA32F:
        return 16;
    default:
        return 0;
    }
}

GLuint fc_gl_nearest_sampler(void)
{
    GLuint sampler = 0;
    glCreateSamplers(1, &sampler);
    glSamplerParameteri(sampler, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glSamplerParameteri(sampler, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glSamplerParameteri(sampler, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(sampler, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return sampler;
}

bool fc_gl_software_rasterizer(void)
{
    const char *renderer = (const char *)glGetString(GL_RENDERER);
    return renderer && (strncmp(renderer, "llvmpipe", 8) == 0 || strncmp(renderer, "softpipe", 8) == 0);
}

void fc_gl_draw_fullscreen(GLuint empty_vertex_array)
{
    glBindVertexArray(empty_vertex_array);
    glDrawArrays(GL_TRIANGLES, 0, 3);
}

static GLuint groups_over(uint32_t pixels, uint32_t per_group)
{
    return (pixels + per_group - 1) / per_group;
}

void fc_gl_dispatch_over_image(uint32_t width, uint32_t height, uint32_t group_width, uint32_t group_height)
{
    glDispatchCompute(groups_over(width, group_width), groups_over(height, group_height), 1);
    /* Image stores are not ordered with later reads by themselves. */
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
}
