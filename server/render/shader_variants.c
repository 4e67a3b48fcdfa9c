/* shader_variants.c — see shader_variants.h. */
#include "shader_variants.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "shader_program.h"

static const char *const feature_defines[FC_SHADER_FEATURE_COUNT] = {
    "FC_HAS_FLOOR", "FC_HAS_SHADOW", "FC_HAS_MESH_SHADOW", "FC_USE_CLIENT_IMAGE",
    "FC_USE_ENVIRONMENT_MAP", "FC_HAS_FOAM", "FC_COLORED", "FC_HAS_NOISE", "FC_FLOOR_ONLY",
    "FC_FLUID_MASK",
};

void fc_shader_defines(unsigned features, char *out, size_t size)
{
    size_t used = (size_t)snprintf(out, size, "#define FC_VARIANT 1\n");
    for (int i = 0; i < FC_SHADER_FEATURE_COUNT && used < size; i++)
        used += (size_t)snprintf(out + used, size - used, "#define %s %d\n", feature_defines[i],
                                 features & (1u << i) ? 1 : 0);
}

static fc_code build(const fc_program_variants *v, unsigned features, fc_program_variant *slot, fc_error *err)
{
    char defines[FC_SHADER_DEFINES_MAX];
    fc_shader_defines(features, defines, sizeof defines);
    GLuint program = 0;
    const fc_program_options options = {.shader_dir = v->shader_dir, .defines = defines,
                                        .flat_constants = v->flat_constants};
    fc_code code = fc_program_build_with(&options, v->files, v->file_count, &program, err);
    if (code != FC_OK)
        return code;
    *slot = (fc_program_variant){.features = features, .program = program,
                                 .uniforms = fc_program_uniform_locations(program)};
    return FC_OK;
}

fc_code fc_program_variants_create(fc_program_variants *v, const fc_program_options *options,
                                   const char *const *files, size_t file_count, unsigned features, fc_error *err)
{
    *v = (fc_program_variants){.files = files, .file_count = file_count, .flat_constants = options->flat_constants};
    if (options->shader_dir && !(v->shader_dir = strdup(options->shader_dir)))
        return fc_error_set(err, FC_ERR_NOMEM, "out of memory for the shader directory's name");
    const fc_program_variant *first = NULL;
    return fc_program_variants_get(v, features, &first, err);
}

void fc_program_variants_destroy(fc_program_variants *v)
{
    for (size_t i = 0; i < FC_PROGRAM_VARIANTS_MAX; i++)
        glDeleteProgram(v->slots[i].program);
    free(v->shader_dir);
    *v = (fc_program_variants){0};
}

fc_code fc_program_variants_get(fc_program_variants *v, unsigned features, const fc_program_variant **out,
                                fc_error *err)
{
    fc_program_variant *free_slot = NULL;
    for (size_t i = 0; i < FC_PROGRAM_VARIANTS_MAX; i++) {
        fc_program_variant *slot = &v->slots[i];
        if (slot->program && slot->features == features) {
            *out = slot;
            return FC_OK;
        }
        if (!slot->program && !free_slot)
            free_slot = slot;
    }
    fc_program_variant built;
    fc_code code = build(v, features, &built, err);
    if (code != FC_OK)
        return code;
    if (!free_slot) {
        free_slot = &v->slots[v->next_evicted];
        v->next_evicted = (v->next_evicted + 1) % FC_PROGRAM_VARIANTS_MAX;
        glDeleteProgram(free_slot->program);
    }
    *free_slot = built;
    *out = free_slot;
    return FC_OK;
}
