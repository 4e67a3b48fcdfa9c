/* background_pass.h — the scene without fluid (the client's background image,
 * else the built-in sky and floor), rendered into its own texture first so the
 * composite pass can sample it at refracted positions (van der Laan et al.
 * 2009, S in eq. 14). */
#ifndef FC_BACKGROUND_PASS_H
#define FC_BACKGROUND_PASS_H

#include <epoxy/gl.h>

#include "environment.h"
#include "render_target.h"
#include "scene_textures.h"

typedef struct fc_background_pass {
    GLuint program;
    GLuint empty_vertex_array;
    fc_render_target target;   /* RGBA16F linear radiance, bilinear so refraction samples smoothly */
} fc_background_pass;

fc_code fc_background_pass_create(const char *shader_dir, fc_background_pass *pass, fc_error *err);
void fc_background_pass_destroy(fc_background_pass *pass);

/* `scene` may be NULL (built-in scene); a background image is scaled to cover
 * the view, keeping its aspect ratio and cropping what overhangs evenly. */
fc_code fc_background_pass_run(fc_background_pass *pass, const fc_view *view, const fc_environment *env,
                               const fc_scene_textures *scene, fc_error *err);

#endif
