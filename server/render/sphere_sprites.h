/* sphere_sprites.h — particles drawn as ray-cast sphere sprites: a point
 * sprite where that is exact, else an instanced quad bounding the projected
 * sphere (sphere_bounds.glsl + sphere.vert.glsl + sphere_ray.glsl + a pass's
 * fragment shader). Where the particle buffer names ellipsoids
 * (fc_particle_buffer.shapes, anisotropy.h) and the sprites were made for
 * them, the same sprites bound each ellipsoid's bounding sphere and cast
 * the ellipsoid (ellipsoid_shape.vert.glsl, ellipsoid_ray.glsl,
 * ellipsoid_shape.frag.glsl): a pass's fragment shader calls
 * cast_particle_ray and particle_normal, which either shape provides.
 * The passes differ only in that shader and GL state. */
#ifndef FC_SPHERE_SPRITES_H
#define FC_SPHERE_SPRITES_H

#include <epoxy/gl.h>

#include "fluidcast_types.h"
#include "particle_buffer.h"
#include "view.h"

typedef struct fc_sphere_sprites {
    GLuint program;             /* spheres */
    GLuint ellipsoid_program;   /* ellipsoids; 0: the sprites draw spheres only */
    float max_point_size;   /* the driver's limit: larger spheres are drawn as quads */
} fc_sphere_sprites;

/* The sphere program of a pass's fragment shader, with a file of helper
 * functions linked in (NULL: none): e.g. particle_attributes.frag.glsl for
 * fragment shaders that read the particle records (bind them with
 * fc_particle_attributes_bind). */
fc_code fc_sphere_sprites_create_with(const char *shader_dir, const char *helper_file, const char *fragment_file,
                                      fc_sphere_sprites *s, fc_error *err);
/* The same, with a second program that draws the ellipsoids where the
 * particles have them. */
fc_code fc_sphere_sprites_create_shaped(const char *shader_dir, const char *helper_file, const char *fragment_file,
                                        fc_sphere_sprites *s, fc_error *err);
void fc_sphere_sprites_destroy(fc_sphere_sprites *s);

/* The program a draw of `particles` uses: set a pass's own uniforms on it. */
GLuint fc_sphere_sprites_program(const fc_sphere_sprites *s, const fc_particle_buffer *particles);

/* Draws every particle as a sphere of `radius` into the bound framebuffer;
 * where the particles are sized (particle_buffer.h), each particle's sphere
 * is `radius` times its ratio to the median. */
void fc_sphere_sprites_draw(const fc_sphere_sprites *s, const fc_particle_buffer *particles, const fc_view *view,
                            float radius);

/* Draws the `count` particles from `first` on (the spray after the surface). */
void fc_sphere_sprites_draw_range(const fc_sphere_sprites *s, const fc_particle_buffer *particles, uint64_t first,
                                  uint64_t count, const fc_view *view, float radius);

#endif
