/* sphere_sprites.c — drawing particles as ray-cast sphere sprites, points
 * and quads (see sphere.vert.glsl for who draws what). */
#include "sphere_sprites.h"

#include "gl_util.h"
#include "shader_program.h"

/* Uniform locations fixed by layout(location) in sphere.vert.glsl. */
enum {
    LOC_VIEW_MATRIX = 0,
    LOC_PROJECTION = 1,
    LOC_VIEWPORT = 2,
    LOC_RADIUS = 3,
    LOC_MAX_POINT_SIZE = 4,
    LOC_AS_QUADS = 5,
    LOC_FIRST_PARTICLE = 9,
    LOC_SIZED_PARTICLES = 512   /* sphere_shape.vert.glsl, ellipsoid_shape.vert.glsl */
};
/* Storage buffer binding of the ellipsoids in ellipsoid_shape.vert.glsl. */
enum { BIND_ELLIPSOIDS = 5 };
/* A quad as a triangle strip. */
#define QUAD_VERTICES 4

/* Links one program from `count` files and records the point size limit. */
static fc_code build(const char *shader_dir, const char *const *files, size_t count, GLuint *program,
                     fc_sphere_sprites *s, fc_error *err)
{
    fc_code code = fc_program_build(shader_dir, files, count, program, err);
    if (code != FC_OK)
        return code;
    GLfloat range[2] = {1.0f, 1.0f};
    glGetFloatv(GL_POINT_SIZE_RANGE, range);
    s->max_point_size = range[1];
    return fc_gl_check("querying the point size range", err);
}

/* The sphere program: the sphere's vertex and fragment sides
 * (sphere_shape.vert.glsl, sphere_shape.frag.glsl) around the shared sprite. */
static fc_code build_spheres(const char *shader_dir, const char *helper_file, const char *fragment_file,
                             fc_sphere_sprites *s, fc_error *err)
{
    const char *files[] = {"sphere_bounds.glsl", "sphere_shape.vert.glsl", "sphere.vert.glsl", "sphere_ray.glsl",
                           "sphere_shape.frag.glsl", helper_file, fragment_file};
    size_t count = sizeof files / sizeof files[0];
    if (!helper_file) {
        files[count - 2] = fragment_file;
        count--;
    }
    return build(shader_dir, files, count, &s->program, s, err);
}

static fc_code build_ellipsoids(const char *shader_dir, const char *helper_file, const char *fragment_file,
                                fc_sphere_sprites *s, fc_error *err)
{
    const char *files[] = {"sphere_bounds.glsl", "ellipsoid_bounds.glsl", "ellipsoid_shape.vert.glsl",
                           "sphere.vert.glsl", "sphere_ray.glsl",
                           "ellipsoid_ray.glsl", "ellipsoid_shape.frag.glsl", helper_file, fragment_file};
    size_t count = sizeof files / sizeof files[0];
    if (!helper_file) {
        files[count - 2] = fragment_file;
        count--;
    }
    return build(shader_dir, files, count, &s->ellipsoid_program, s, err);
}

fc_code fc_sphere_sprites_create_with(const char *shader_dir, const char *helper_file, const char *fragment_file,
                                      fc_sphere_sprites *s, fc_error *err)
{
    *s = (fc_sphere_sprites){0};
    return build_spheres(shader_dir, helper_file, fragment_file, s, err);
}

fc_code fc_sphere_sprites_create_shaped(const char *shader_dir, const char *helper_file, const char *fragment_file,
                                        fc_sphere_sprites *s, fc_error *err)
{
    fc_code code = fc_sphere_sprites_create_with(shader_dir, helper_file, fragment_file, s, err);
    return code == FC_OK ? build_ellipsoids(shader_dir, helper_file, fragment_file, s, err) : code;
}

GLuint fc_sphere_sprites_program(const fc_sphere_sprites *s, const fc_particle_buffer *particles)
{
    return particles->shapes && s->ellipsoid_program ? s->ellipsoid_program : s->program;
}

void fc_sphere_sprites_destroy(fc_sphere_sprites *s)
{
    glDeleteProgram(s->program);
    glDeleteProgram(s->ellipsoid_program);
    *s = (fc_sphere_sprites){0};
}

void fc_sphere_sprites_draw(const fc_sphere_sprites *s, const fc_particle_buffer *particles, const fc_view *view,
                            float radius)
{
    fc_sphere_sprites_draw_range(s, particles, 0, particles->count, view, radius);
}

/* Points for most particles: on llvmpipe one point costs less than the two
 * triangles of a quad (64k particles at 64x36 pixels, where the primitives
 * are the whole cost: 49 ms as points, 68 ms as quads). */
void fc_sphere_sprites_draw_range(const fc_sphere_sprites *s, const fc_particle_buffer *particles, uint64_t first,
                                  uint64_t count, const fc_view *view, float radius)
{
    if (count == 0 || first + count > particles->count)
        return;
    GLuint program = fc_sphere_sprites_program(s, particles);
    glUseProgram(program);
    if (program == s->ellipsoid_program)
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, BIND_ELLIPSOIDS, particles->shapes);
    glUniformMatrix4fv(LOC_VIEW_MATRIX, 1, GL_FALSE, view->view);
    glUniform4f(LOC_PROJECTION, view->fx, view->fy, view->p22, view->p32);
    glUniform2f(LOC_VIEWPORT, (float)view->width, (float)view->height);
    glUniform1f(LOC_RADIUS, radius);
    glUniform1i(LOC_SIZED_PARTICLES, particles->sized ? GL_TRUE : GL_FALSE);
    fc_particle_buffer_bind_radii(particles);
    glUniform1f(LOC_MAX_POINT_SIZE, s->max_point_size);
    glUniform1i(LOC_FIRST_PARTICLE, (GLint)first);
    glEnable(GL_PROGRAM_POINT_SIZE);
    glUniform1i(LOC_AS_QUADS, GL_FALSE);
    fc_particle_buffer_bind(particles, false);
    glDrawArrays(GL_POINTS, (GLint)first, (GLsizei)count);
    glUniform1i(LOC_AS_QUADS, GL_TRUE);
    fc_particle_buffer_bind(particles, true);
    glDrawArraysInstancedBaseInstance(GL_TRIANGLE_STRIP, 0, QUAD_VERTICES, (GLsizei)count, (GLuint)first);
}
