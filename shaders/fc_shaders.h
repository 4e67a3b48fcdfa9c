/* fc_shaders.h — the GLSL sources of shaders/ as built into the binary. */
#ifndef FC_SHADERS_H
#define FC_SHADERS_H

/* The NUL-terminated source of the shader file `name` (e.g. "sphere.vert.glsl"),
 * or NULL when no such file was embedded. */
const char *fc_shader_builtin(const char *name);

#endif
