/* shader_program.c — loading, compiling and linking GLSL programs. */
#include "shader_program.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "fc_file.h"
#include "fc_shaders.h"
#include "flat_constants.h"
#include "gl_util.h"

/* Shaders sharing a stage are linked as separate compilation units; no
 * program of ours needs more files than this. */
#define MAX_PROGRAM_FILES 10
#define INFO_LOG_MAX 1024

static int ends_with(const char *text, const char *suffix)
{
    size_t n = strlen(text), m = strlen(suffix);
    return n >= m && strcmp(text + n - m, suffix) == 0;
}

GLenum fc_shader_stage(const char *file)
{
    if (ends_with(file, ".vert.glsl"))
        return GL_VERTEX_SHADER;
    if (ends_with(file, ".frag.glsl"))
        return GL_FRAGMENT_SHADER;
    if (ends_with(file, ".comp.glsl"))
        return GL_COMPUTE_SHADER;
    return 0;
}

/* A shader from --shader-dir; a file that cannot be read fails the pipeline
 * as any other shader failure does (FC_ERR_GL), memory apart. */
static fc_code read_file(const char *dir, const char *file, char **text, fc_error *err)
{
    char path[4096];
    if (snprintf(path, sizeof path, "%s/%s", dir, file) >= (int)sizeof path)
        return fc_error_set(err, FC_ERR_GL, "shader path too long: %s/%s", dir, file);
    uint8_t *data = NULL;
    size_t size = 0;
    fc_error read_err;
    fc_code code = fc_read_file(path, SIZE_MAX, &data, &size, &read_err);
    if (code != FC_OK)
        return fc_error_set(err, code == FC_ERR_NOMEM ? FC_ERR_NOMEM : FC_ERR_GL, "shader %s", read_err.message);
    *text = (char *)data;
    return FC_OK;
}

/* The source of `file`; *owned is the buffer to free (NULL for built-ins). */
static fc_code load_source(const char *dir, const char *file, const char **source, char **owned, fc_error *err)
{
    *owned = NULL;
    if (dir) {
        fc_code code = read_file(dir, file, owned, err);
        *source = *owned;
        return code;
    }
    *source = fc_shader_builtin(file);
    if (!*source)
        return fc_error_set(err, FC_ERR_GL, "shader %s is not built into this binary", file);
    return FC_OK;
}

/* The source as the strings glShaderSource takes: the #version line, the
 * defines, a #line directive that keeps the driver's line numbers those of
 * the file, and the rest. Every shader of ours starts with #version. */
static GLsizei split_source(const char *source, const char *defines, const char *strings[4])
{
    if (!defines) {
        strings[0] = source;
        return 1;
    }
    const char *rest = strchr(source, '\n');
    rest = rest ? rest + 1 : source + strlen(source);
    strings[0] = source;
    strings[1] = defines;
    strings[2] = "\n#line 2\n";
    strings[3] = rest;
    return 4;
}

static fc_code compile(const char *source, const char *defines, const char *file, GLenum stage, GLuint *shader,
                       fc_error *err)
{
    const char *strings[4];
    GLint lengths[4] = {-1, -1, -1, -1};
    GLsizei n = split_source(source, defines, strings);
    if (n > 1)
        lengths[0] = (GLint)(strings[3] - source);   /* the #version line alone */
    GLuint s = glCreateShader(stage);
    glShaderSource(s, n, strings, lengths);
    glCompileShader(s);
    GLint ok = GL_FALSE;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[INFO_LOG_MAX] = "";
        glGetShaderInfoLog(s, sizeof log, NULL, log);
        glDeleteShader(s);
        return fc_error_set(err, FC_ERR_GL, "compiling %s: %s", file, log);
    }
    *shader = s;
    return FC_OK;
}

static fc_code link(GLuint program, const char *const *files, size_t count, fc_error *err)
{
    glLinkProgram(program);
    GLint ok = GL_FALSE;
    glGetProgramiv(program, GL_LINK_STATUS, &ok);
    if (ok)
        return FC_OK;
    char log[INFO_LOG_MAX] = "";
    glGetProgramInfoLog(program, sizeof log, NULL, log);
    char names[256] = "";
    for (size_t i = 0; i < count; i++)
        snprintf(names + strlen(names), sizeof names - strlen(names), "%s%s", i ? " + " : "", files[i]);
    return fc_error_set(err, FC_ERR_GL, "linking %s: %s", names, log);
}

/* The stage files[i] is compiled for: its own, or for a library without a
 * stage suffix that of the next file with one, so one library can serve the
 * vertex and the fragment stage of a program. */
static GLenum library_stage(const char *const *files, size_t count, size_t i)
{
    GLenum stage = 0;
    while (i < count && !(stage = fc_shader_stage(files[i])))
        i++;
    return stage;
}

fc_code fc_program_build(const char *shader_dir, const char *const *files, size_t count, GLuint *program,
                         fc_error *err)
{
    return fc_program_build_defines(shader_dir, NULL, files, count, program, err);
}

fc_code fc_program_build_defines(const char *shader_dir, const char *defines, const char *const *files, size_t count,
                                 GLuint *program, fc_error *err)
{
    const fc_program_options options = {.shader_dir = shader_dir, .defines = defines};
    return fc_program_build_with(&options, files, count, program, err);
}

/* A program's sources as loaded, and what building it adds: the flat
 * constants' rewritten fragment sources, their vertex-stage unit and the
 * defines with FC_FLAT_CONSTANTS. */
typedef struct program_sources {
    const char *text[MAX_PROGRAM_FILES];
    char *owned[MAX_PROGRAM_FILES];
    GLenum stage[MAX_PROGRAM_FILES];
    char *forward;    /* the vertex-stage unit of flat_constants.h, NULL without */
    char *defines;    /* owned; NULL: none */
} program_sources;

static void free_sources(program_sources *s, size_t count)
{
    for (size_t i = 0; i < count; i++)
        free(s->owned[i]);
    free(s->forward);
    free(s->defines);
}

static fc_code copy_defines(const char *defines, bool flat, char **out, fc_error *err)
{
    static const char flat_define[] = "#define FC_FLAT_CONSTANTS 1\n";
    *out = NULL;
    if (!defines && !flat)
        return FC_OK;
    size_t n = (defines ? strlen(defines) : 0) + (flat ? sizeof flat_define : 1);
    if (!(*out = malloc(n)))
        return fc_error_set(err, FC_ERR_NOMEM, "out of memory for a shader's defines");
    snprintf(*out, n, "%s%s", defines ? defines : "", flat ? flat_define : "");
    return FC_OK;
}

/* The locations a vertex stage can hand the fragment stage. */
static int varying_locations(void)
{
    GLint fragment = 0, vertex = 0;
    glGetIntegerv(GL_MAX_FRAGMENT_INPUT_COMPONENTS, &fragment);
    glGetIntegerv(GL_MAX_VERTEX_OUTPUT_COMPONENTS, &vertex);
    return (fragment < vertex ? fragment : vertex) / 4;
}

/* Rewrites the fragment-stage sources in place (flat_constants.h) and
 * generates the vertex-stage unit that feeds them. */
static fc_code flatten(program_sources *s, const char *const *files, size_t count, fc_error *err)
{
    bool has_vertex = false;
    for (size_t i = 0; i < count; i++)
        has_vertex = has_vertex || s->stage[i] == GL_VERTEX_SHADER;
    if (!has_vertex)
        return fc_error_set(err, FC_ERR_GL, "flat constants need a vertex shader to forward them");
    fc_flat_constants *constants = calloc(1, sizeof *constants);
    if (!constants)
        return fc_error_set(err, FC_ERR_NOMEM, "out of memory for a shader's flat constants");
    fc_code code = FC_OK;
    for (size_t i = 0; i < count && code == FC_OK; i++)
        if (s->stage[i] == GL_FRAGMENT_SHADER)
            code = fc_flat_constants_collect(constants, s->text[i], files[i], err);
    if (code == FC_OK)
        fc_flat_constants_assign(constants, varying_locations());
    for (size_t i = 0; i < count && code == FC_OK; i++) {
        if (s->stage[i] != GL_FRAGMENT_SHADER)
            continue;
        char *rewritten = NULL;
        code = fc_flat_constants_rewrite(constants, s->text[i], &rewritten, err);
        if (code == FC_OK) {
            free(s->owned[i]);
            s->text[i] = s->owned[i] = rewritten;
        }
    }
    if (code == FC_OK)
        code = fc_flat_constants_vertex_source(constants, &s->forward, err);
    free(constants);
    return code;
}

static fc_code load_sources(const fc_program_options *o, const char *const *files, size_t count, program_sources *s,
                            fc_error *err)
{
    *s = (program_sources){0};
    fc_code code = copy_defines(o->defines, o->flat_constants, &s->defines, err);
    for (size_t i = 0; i < count && code == FC_OK; i++) {
        s->stage[i] = library_stage(files, count, i);
        code = load_source(o->shader_dir, files[i], &s->text[i], &s->owned[i], err);
    }
    if (code == FC_OK && o->flat_constants)
        code = flatten(s, files, count, err);
    return code;
}

fc_code fc_program_build_with(const fc_program_options *options, const char *const *files, size_t count,
                              GLuint *program, fc_error *err)
{
    if (count == 0 || count > MAX_PROGRAM_FILES)
        return fc_error_set(err, FC_ERR_USAGE, "a program needs 1 to %d shader files, got %zu",
                            MAX_PROGRAM_FILES, count);
    GLenum last_stage = fc_shader_stage(files[count - 1]);
    if (!last_stage)
        return fc_error_set(err, FC_ERR_GL, "shader %s: no stage suffix (.vert.glsl, .frag.glsl, .comp.glsl)",
                            files[count - 1]);
    program_sources sources;
    fc_code code = load_sources(options, files, count, &sources, err);
    GLuint shaders[MAX_PROGRAM_FILES + 1] = {0};
    GLuint p = glCreateProgram();
    for (size_t i = 0; i < count && code == FC_OK; i++) {
        code = compile(sources.text[i], sources.defines, files[i], sources.stage[i], &shaders[i], err);
        if (code == FC_OK)
            glAttachShader(p, shaders[i]);
    }
    if (code == FC_OK && sources.forward) {
        code = compile(sources.forward, sources.defines, "(flat constants)", GL_VERTEX_SHADER, &shaders[count], err);
        if (code == FC_OK)
            glAttachShader(p, shaders[count]);
    }
    free_sources(&sources, count);
    if (code == FC_OK)
        code = link(p, files, count, err);
    /* The linked program keeps what it needs; the shader objects can go. */
    for (size_t i = 0; i <= count; i++)
        glDeleteShader(shaders[i]);
    if (code == FC_OK)
        code = fc_gl_check("building a shader program", err);
    if (code != FC_OK) {
        glDeleteProgram(p);
        return code;
    }
    *program = p;
    return FC_OK;
}

/* Whether uniforms of `type` hold values (scalars, vectors, matrices) rather
 * than name a texture unit or an image. */
static bool is_value_type(GLenum type)
{
    switch (type) {
    case GL_FLOAT: case GL_FLOAT_VEC2: case GL_FLOAT_VEC3: case GL_FLOAT_VEC4:
    case GL_INT: case GL_INT_VEC2: case GL_INT_VEC3: case GL_INT_VEC4:
    case GL_UNSIGNED_INT: case GL_UNSIGNED_INT_VEC2: case GL_UNSIGNED_INT_VEC3: case GL_UNSIGNED_INT_VEC4:
    case GL_BOOL: case GL_BOOL_VEC2: case GL_BOOL_VEC3: case GL_BOOL_VEC4:
    case GL_FLOAT_MAT2: case GL_FLOAT_MAT3: case GL_FLOAT_MAT4:
    case GL_FLOAT_MAT2x3: case GL_FLOAT_MAT2x4: case GL_FLOAT_MAT3x2:
    case GL_FLOAT_MAT3x4: case GL_FLOAT_MAT4x2: case GL_FLOAT_MAT4x3:
        return true;
    default:
        return false;
    }
}

/* Samplers (bound by layout(binding), never set) are left out: the driver
 * gives them locations of its own choosing, which may be one that a variant's
 * missing uniform leaves free, and a setter must not mistake one for it. */
uint64_t fc_program_uniform_locations(GLuint program)
{
    GLint count = 0;
    glGetProgramInterfaceiv(program, GL_UNIFORM, GL_ACTIVE_RESOURCES, &count);
    uint64_t active = 0;
    const GLenum properties[] = {GL_LOCATION, GL_TYPE};
    for (GLint i = 0; i < count; i++) {
        GLint values[2] = {-1, 0};
        glGetProgramResourceiv(program, GL_UNIFORM, (GLuint)i, 2, properties, 2, NULL, values);
        if (values[0] >= 0 && values[0] < 64 && is_value_type((GLenum)values[1]))
            active |= UINT64_C(1) << values[0];
    }
    return active;
}
