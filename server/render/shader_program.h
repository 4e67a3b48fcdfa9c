/* shader_program.h — GL programs linked from shader files of shaders/, taken
 * from the binary or, for development, from a directory on disk. */
#ifndef FC_SHADER_PROGRAM_H
#define FC_SHADER_PROGRAM_H

#include <epoxy/gl.h>
#include <stddef.h>

#include "fluidcast_types.h"

/* The stage a shader file's suffix names: GL_VERTEX_SHADER, GL_FRAGMENT_SHADER,
 * GL_COMPUTE_SHADER; 0 for a library. */
GLenum fc_shader_stage(const char *file);

/* Compiles each of `files` (the stage comes from the name: *.vert.glsl,
 * *.frag.glsl, *.comp.glsl; several files may share a stage, one of them with
 * main) and links them into *program. A library without a stage suffix
 * (*.glsl) is compiled for the stage of the next file that names one (the
 * last file must): fragment and compute programs share such code, and so do
 * the vertex and fragment stages of one program. `shader_dir` NULL uses the
 * built-in copies. FC_ERR_GL with the file name and the driver's info log on
 * failure. */
fc_code fc_program_build(const char *shader_dir, const char *const *files, size_t count, GLuint *program,
                         fc_error *err);

#endif
