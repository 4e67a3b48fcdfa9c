/* sphere_sprites.h — particles drawn as ray-cast sphere sprites
 * (sphere.vert.glsl + sphere_ray.frag.glsl + a pass's fragment shader).
 * The depth and thickness passes differ only in that shader and GL state. */
#ifndef FC_SPHERE_SPRITES_H
#define FC_SPHERE_SPRITES_H

#include <epoxy/gl.h>

#include "fluidcast_types.h"
#include "particle_buffer.h"
#include "view.h"

typedef struct fc_sphere_sprites {
    GLuint program;
    float max_point_size;   /* the driver's limit: larger spheres are cut to it */
} fc_sphere_sprites;

fc_code fc_sphere_sprites_create(const char *shader_dir, const char *fragment_file, fc_sphere_sprites *s,
                                 fc_error *err);
/* The same with particle_attributes.frag.glsl linked in, for fragment shaders
 * that read the particle records (bind them with fc_particle_attributes_bind). */
fc_code fc_sphere_sprites_create_with_records(const char *shader_dir, const char *fragment_file,
                                              fc_sphere_sprites *s, fc_error *err);
void fc_sphere_sprites_destroy(fc_sphere_sprites *s);

/* Draws every particle as a sphere of `radius` into the bound framebuffer. */
void fc_sphere_sprites_draw(const fc_sphere_sprites *s, const fc_particle_buffer *particles, const fc_view *view,
                            float radius);

/* Draws the `count` particles from `first` on (the spray after the surface). */
void fc_sphere_sprites_draw_range(const fc_sphere_sprites *s, const fc_particle_buffer *particles, uint64_t first,
                                  uint64_t count, const fc_view *view, float radius);

#endif
