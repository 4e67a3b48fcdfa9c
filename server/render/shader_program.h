/* shader_program.h — GL programs linked from shader files of shaders/, taken
 * from the binary or, for development, from a directory on disk. */
#ifndef FC_SHADER_PROGRAM_H
#define FC_SHADER_PROGRAM_H

#include <epoxy/gl.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

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

/* fc_program_build with `defines` (preprocessor lines, e.g. "#define FC_X 1")
 * placed after the #version line of every file; NULL: none. Line numbers in
 * the driver's messages stay those of the files. */
fc_code fc_program_build_defines(const char *shader_dir, const char *defines, const char *const *files, size_t count,
                                 GLuint *program, fc_error *err);

/* How a program is built: where its files come from, preprocessor lines
 * placed after the #version line of every file (e.g. "#define FC_X 1\n";
 * NULL: none; line numbers in the driver's messages stay those of the
 * files), and whether the fragment stage's uniforms reach it as flat inputs
 * (flat_constants.h: then FC_FLAT_CONSTANTS is defined too, and one of the
 * files must be a vertex shader that calls fc_forward_constants() under it). */
typedef struct fc_program_options {
    const char *shader_dir;   /* NULL: the built-in copies */
    const char *defines;
    bool flat_constants;
} fc_program_options;

fc_code fc_program_build_with(const fc_program_options *options, const char *const *files, size_t count,
                              GLuint *program, fc_error *err);

/* The active uniforms of a linked program among the explicit locations 0..63,
 * as bits (bit L: location L). The compiler drops the uniforms a program does
 * not use (all of a feature a shader variant leaves out), and setting one of
 * those is GL_INVALID_OPERATION with some drivers: setters check this first. */
uint64_t fc_program_uniform_locations(GLuint program);

/* Every location: for programs whose uniforms are all in use. */
#define FC_ALL_UNIFORMS UINT64_MAX

static inline bool fc_uniform_active(uint64_t uniforms, int location)
{
    return location >= 0 && location < 64 && ((uniforms >> location) & 1u);
}

#endif
