/* mesh_write.c — see mesh_write.h: the format by extension, the file written
 * whole or not at all. */
#include "mesh_write.h"

#include <errno.h>
#include <stdbool.h>
#include <stdio.h>
#include <string.h>
#include <strings.h>

#include "fc_error.h"

static const struct {
    const char *extension;
    fc_mesh_file_format format;
} extensions[] = {{".ply", FC_MESH_FILE_PLY}, {".obj", FC_MESH_FILE_OBJ}, {".vtp", FC_MESH_FILE_VTP},
                  {".stl", FC_MESH_FILE_STL}};

fc_code fc_mesh_file_format_of(const char *path, fc_mesh_file_format *out, fc_error *err)
{
    const char *dot = strrchr(path, '.');
    for (size_t i = 0; dot && i < sizeof extensions / sizeof extensions[0]; i++)
        if (strcasecmp(dot, extensions[i].extension) == 0) {
            *out = extensions[i].format;
            return FC_OK;
        }
    return fc_error_set(err, FC_ERR_USAGE, "%s: a mesh file is .ply, .obj, .vtp or .stl", path);
}

static fc_code write_format(FILE *to, fc_mesh_file_format format, const fc_surface_mesh *mesh, fc_error *err)
{
    switch (format) {
    case FC_MESH_FILE_PLY: return fc_mesh_write_ply(to, mesh, err);
    case FC_MESH_FILE_OBJ: return fc_mesh_write_obj(to, mesh, err);
    case FC_MESH_FILE_VTP: return fc_mesh_write_vtp(to, mesh, err);
    case FC_MESH_FILE_STL: return fc_mesh_write_stl(to, mesh, err);
    }
    return fc_error_set(err, FC_ERR_USAGE, "unknown mesh file format %d", (int)format);
}

fc_code fc_mesh_write_file(const char *path, const fc_surface_mesh *mesh, fc_error *err)
{
    fc_mesh_file_format format;
    fc_code code = fc_mesh_file_format_of(path, &format, err);
    if (code != FC_OK)
        return code;
    char part[4096];
    if (snprintf(part, sizeof part, "%s.part", path) >= (int)sizeof part)
        return fc_error_set(err, FC_ERR_USAGE, "%s: path too long", path);
    FILE *to = fopen(part, "wb");
    if (!to)
        return fc_error_set(err, FC_ERR_IO, "cannot create %s: %s", part, strerror(errno));
    fc_error why;
    code = write_format(to, format, mesh, &why);
    bool closed = fclose(to) == 0;
    if (code == FC_OK && !closed)
        code = fc_error_set(&why, FC_ERR_IO, "%s", strerror(errno));
    if (code == FC_OK && rename(part, path) != 0)
        code = fc_error_set(&why, FC_ERR_IO, "cannot rename %s: %s", part, strerror(errno));
    if (code != FC_OK) {
        remove(part);
        return fc_error_set(err, code, "writing %s: %s", path, why.message);
    }
    return FC_OK;
}
