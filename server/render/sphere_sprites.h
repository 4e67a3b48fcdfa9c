/* sphere_sprites.h — particles drawn as ray-cast sphere sprites: a point
 * sprite where that is exact, else an instanced quad bounding the projected
 * sphere (sphere_bounds.glsl + sphere.vert.glsl + sphere_ray.glsl + a pass's
 * fragment shader).
 * The passes differ only in that shader and GL state. */
#ifndef FC_SPHERE_SPRITES_H
#define FC_SPHERE_SPRITES_H

#include <epoxy/gl.h>

#include "fluidcast_types.h"
#include "particle_buffer.h"
#include "view.h"

typedef struct fc_sphere_sprites {
    GLuint program;
    float max_point_size;   /* the driver's limit: larger spheres are drawn as quads */
} fc_sphere_sprites;

fc_code fc_sphere_sprites_create(const char *shader_dir, const char *fragment_file, fc_sphere_sprites *s,
                                 fc_error *err);
/* The same with a file of helper functions linked in: e.g.
 * particle_attributes.frag.glsl for fragment shaders that read the particle
 * records (bind them with fc_particle_attributes_bind). */
fc_code fc_sphere_sprites_create_with(const char *shader_dir, const char *helper_file, const char *fragment_file,
                                      fc_sphere_sprites *s, fc_error *err);
void fc_sphere_sprites_destroy(fc_sphere_sprites *s);

/* Draws every particle as a sphere of `radius` into the bound framebuffer. */
void fc_sphere_sprites_draw(const fc_sphere_sprites *s, const fc_particle_buffer *particles, const fc_view *view,
                            float radius);

/* Draws the `count` particles from `first` on (the spray after the surface). */
void fc_sphere_sprites_draw_range(const fc_sphere_sprites *s, const fc_particle_buffer *particles, uint64_t first,
                                  uint64_t count, const fc_view *view, float radius);

#endif
