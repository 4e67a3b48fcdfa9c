/* fc_surface_mesh.c — releasing an extracted surface (fc_surface_mesh.h). */
#include "fc_surface_mesh.h"

#include <stdlib.h>
#include <string.h>

void fc_surface_mesh_free(fc_surface_mesh *mesh)
{
    free(mesh->positions);
    free(mesh->normals);
    free(mesh->indices);
    free(mesh->speed);
    free(mesh->density);
    free(mesh->velocity);
    free(mesh->id);
    memset(mesh, 0, sizeof *mesh);
}
