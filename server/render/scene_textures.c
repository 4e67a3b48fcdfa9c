/* scene_textures.c — a client's background image and environment cube map on the GPU. */
#include "scene_textures.h"

#include <stdbool.h>
#include <stdlib.h>

#include "fc_error.h"
#include "gl_util.h"

#define CUBE_FACES 6

typedef struct texel_format {
    GLenum internal;   /* sRGB for 8-bit images, so sampling returns linear values; always with alpha,
                          which every GL can render to and so build mipmaps of */
    GLenum format;
    GLenum type;
} texel_format;

static fc_code check_image(const fc_image *img, const char *what, fc_error *err)
{
    if (!img->pixels || img->width == 0 || img->height == 0)
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "%s: empty image", what);
    if (img->channels != 3 && img->channels != 4)
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "%s: %u channels (expected RGB or RGBA)", what,
                            img->channels);
    if (img->type != FC_PIXEL_U8 && img->type != FC_PIXEL_F32)
        return fc_error_set(err, FC_ERR_INVALID_VALUE, "%s: unknown pixel type %d", what, (int)img->type);
    return FC_OK;
}

static fc_code check_size(uint32_t width, uint32_t height, GLenum limit_name, const char *what, fc_error *err)
{
    GLint limit = 0;
    glGetIntegerv(limit_name, &limit);
    if (width > (uint32_t)limit || height > (uint32_t)limit)
        return fc_error_set(err, FC_ERR_LIMIT, "%s: %ux%u exceeds this GPU's %d pixels per side", what, width,
                            height, (int)limit);
    return FC_OK;
}

static texel_format format_of(const fc_image *img)
{
    bool rgba = img->channels == 4;
    if (img->type == FC_PIXEL_U8)
        return (texel_format){GL_SRGB8_ALPHA8, rgba ? GL_RGBA : GL_RGB, GL_UNSIGNED_BYTE};
    return (texel_format){GL_RGBA32F, rgba ? GL_RGBA : GL_RGB, GL_FLOAT};
}

/* A full mip chain: a background larger than the image, or a reflection of
 * a curved surface, minifies the texture and would alias without one. */
static GLsizei mip_levels(uint32_t width, uint32_t height)
{
    uint32_t size = width > height ? width : height;
    GLsizei levels = 1;
    while (size >>= 1)
        levels++;
    return levels;
}

static void set_sampling(GLuint texture)
{
    glTextureParameteri(texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
    glTextureParameteri(texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    glGenerateTextureMipmap(texture);
}

static fc_code create_background(const fc_image *img, fc_scene_textures *t, fc_error *err)
{
    fc_code code = check_image(img, "background", err);
    if (code == FC_OK)
        code = check_size(img->width, img->height, GL_MAX_TEXTURE_SIZE, "background", err);
    if (code != FC_OK)
        return code;
    texel_format f = format_of(img);
    glCreateTextures(GL_TEXTURE_2D, 1, &t->background);
    glTextureStorage2D(t->background, mip_levels(img->width, img->height), f.internal, (GLsizei)img->width,
                       (GLsizei)img->height);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(t->background, 0, 0, 0, (GLsizei)img->width, (GLsizei)img->height, f.format, f.type,
                        img->pixels);
    set_sampling(t->background);
    t->background_aspect = (float)img->width / (float)img->height;
    return fc_gl_check("uploading the background image", err);
}

static fc_code check_faces(const fc_image *faces, fc_error *err)
{
    for (int i = 0; i < CUBE_FACES; i++) {
        fc_code code = check_image(&faces[i], "cube map face", err);
        if (code != FC_OK)
            return code;
        if (faces[i].width != faces[i].height)
            return fc_error_set(err, FC_ERR_INVALID_VALUE, "cube map face %d is %ux%u, not square", i,
                                faces[i].width, faces[i].height);
        if (faces[i].width != faces[0].width || faces[i].channels != faces[0].channels ||
            faces[i].type != faces[0].type)
            return fc_error_set(err, FC_ERR_INVALID_VALUE,
                                "cube map face %d differs from face 0 in size, channels or pixel type", i);
    }
    return check_size(faces[0].width, faces[0].height, GL_MAX_CUBE_MAP_TEXTURE_SIZE, "cube map face", err);
}

/* Faces are uploaded as they are: in the OpenGL cube-map convention a face's
 * first row is its top, as in fc_image. */
static fc_code create_environment_map(const fc_image *faces, fc_scene_textures *t, fc_error *err)
{
    fc_code code = check_faces(faces, err);
    if (code != FC_OK)
        return code;
    texel_format f = format_of(&faces[0]);
    GLsizei size = (GLsizei)faces[0].width;
    glCreateTextures(GL_TEXTURE_CUBE_MAP, 1, &t->environment_map);
    glTextureStorage2D(t->environment_map, mip_levels(faces[0].width, faces[0].height), f.internal, size, size);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    for (int i = 0; i < CUBE_FACES; i++)
        glTextureSubImage3D(t->environment_map, 0, 0, 0, i, size, size, 1, f.format, f.type, faces[i].pixels);
    set_sampling(t->environment_map);
    return fc_gl_check("uploading the cube map", err);
}

fc_code fc_scene_textures_create(fc_pipeline *p, const fc_image *background, const fc_image *faces,
                                 fc_scene_textures **out, fc_error *err)
{
    if (!p || !out)
        return fc_error_set(err, FC_ERR_USAGE, "fc_scene_textures_create: missing pipeline or output");
    *out = NULL;
    fc_scene_textures *t = calloc(1, sizeof *t);
    if (!t)
        return fc_error_set(err, FC_ERR_NOMEM, "out of memory for scene textures");
    fc_code code = background ? create_background(background, t, err) : FC_OK;
    if (code == FC_OK && faces)
        code = create_environment_map(faces, t, err);
    if (code != FC_OK) {
        fc_scene_textures_destroy(t);
        return code;
    }
    *out = t;
    return FC_OK;
}

void fc_scene_textures_destroy(fc_scene_textures *t)
{
    if (!t)
        return;
    glDeleteTextures(1, &t->background);
    glDeleteTextures(1, &t->environment_map);
    free(t);
}
