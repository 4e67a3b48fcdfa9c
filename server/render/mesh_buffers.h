/* mesh_buffers.h — the layout of fc_mesh_buffers (pipeline.h): one client
 * mesh's vertices, optional normals and indices on the GPU, for the passes
 * that draw it (mesh_pass.h). */
#ifndef FC_MESH_BUFFERS_H
#define FC_MESH_BUFFERS_H

#include <epoxy/gl.h>
#include <stdbool.h>
#include <stdint.h>

#include "pipeline.h"

struct fc_mesh_buffers {
    GLuint vertex_array;   /* attribute 0 positions, 1 normals (when present) */
    GLuint positions;
    GLuint normals;        /* 0 without normals: triangles are shaded flat */
    GLuint indices;
    GLsizei index_count;   /* 3 T */
    float lo[3], hi[3];    /* bounds of the vertices, in the mesh's own frame */
};

#endif
