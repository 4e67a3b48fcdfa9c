/* mesh_buffers.c — a client mesh copied to the GPU (pipeline.h, mesh_buffers.h). */
#include "mesh_buffers.h"

#include <stdlib.h>

#include "fc_error.h"
#include "gl_util.h"

static void measure_bounds(const fc_mesh *mesh, fc_mesh_buffers *b)
{
    for (int k = 0; k < 3; k++) {
        b->lo[k] = mesh->vertices[k];
        b->hi[k] = mesh->vertices[k];
    }
    for (uint32_t i = 1; i < mesh->vertex_count; i++)
        for (int k = 0; k < 3; k++) {
            float v = mesh->vertices[3 * (size_t)i + k];
            b->lo[k] = v < b->lo[k] ? v : b->lo[k];
            b->hi[k] = v > b->hi[k] ? v : b->hi[k];
        }
}

/* One float3 attribute from its own buffer. */
static void attach(GLuint vertex_array, GLuint attribute, GLuint buffer)
{
    glVertexArrayVertexBuffer(vertex_array, attribute, buffer, 0, 3 * sizeof(float));
    glVertexArrayAttribFormat(vertex_array, attribute, 3, GL_FLOAT, GL_FALSE, 0);
    glVertexArrayAttribBinding(vertex_array, attribute, attribute);
    glEnableVertexArrayAttrib(vertex_array, attribute);
}

fc_code fc_mesh_buffers_create(fc_pipeline *p, const fc_mesh *mesh, fc_mesh_buffers **out, fc_error *err)
{
    (void)p;   /* made in the pipeline's context, which must be current */
    *out = NULL;
    if (!mesh || mesh->triangle_count == 0 || !mesh->vertices || !mesh->indices)
        return fc_error_set(err, FC_ERR_USAGE, "fc_mesh_buffers_create: a mesh with triangles is needed");
    fc_mesh_buffers *b = calloc(1, sizeof *b);
    if (!b)
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for mesh %u", (unsigned)mesh->id);
    size_t vertex_bytes = 12 * (size_t)mesh->vertex_count, index_bytes = 12 * (size_t)mesh->triangle_count;
    glCreateVertexArrays(1, &b->vertex_array);
    glCreateBuffers(1, &b->positions);
    glCreateBuffers(1, &b->indices);
    glNamedBufferStorage(b->positions, (GLsizeiptr)vertex_bytes, mesh->vertices, 0);
    glNamedBufferStorage(b->indices, (GLsizeiptr)index_bytes, mesh->indices, 0);
    attach(b->vertex_array, 0, b->positions);
    if (mesh->normals) {
        glCreateBuffers(1, &b->normals);
        glNamedBufferStorage(b->normals, (GLsizeiptr)vertex_bytes, mesh->normals, 0);
        attach(b->vertex_array, 1, b->normals);
    }
    glVertexArrayElementBuffer(b->vertex_array, b->indices);
    b->index_count = (GLsizei)(3 * mesh->triangle_count);
    measure_bounds(mesh, b);
    fc_code code = fc_gl_check("uploading a mesh", err);
    if (code != FC_OK) {
        fc_mesh_buffers_destroy(b);
        return code;
    }
    *out = b;
    return FC_OK;
}

void fc_mesh_buffers_destroy(fc_mesh_buffers *b)
{
    if (!b)
        return;
    glDeleteVertexArrays(1, &b->vertex_array);
    glDeleteBuffers(1, &b->positions);
    glDeleteBuffers(1, &b->normals);
    glDeleteBuffers(1, &b->indices);
    free(b);
}
