/* mesh_reader.c — see mesh_reader.h: the format from the name, the file into memory. */
#include "mesh_reader.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "fc_error.h"
#include "fc_file.h"
#include "mesh_formats.h"

fc_mesh_format fc_mesh_format_from_path(const char *path)
{
    const char *dot = strrchr(path, '.');
    if (!dot)
        return FC_MESH_FILE_UNKNOWN;
    static const struct {
        const char *ext;
        fc_mesh_format format;
    } table[] = {{".obj", FC_MESH_FILE_OBJ}, {".stl", FC_MESH_FILE_STL}, {".ply", FC_MESH_FILE_PLY},
                 {".vtk", FC_MESH_FILE_VTK}, {".vtp", FC_MESH_FILE_VTP}};
    for (size_t i = 0; i < sizeof table / sizeof table[0]; i++)
        if (strcasecmp(dot, table[i].ext) == 0)
            return table[i].format;
    return FC_MESH_FILE_UNKNOWN;
}

fc_code fc_read_mesh_mem(const char *name, const uint8_t *data, size_t size, fc_mesh_data *out, fc_error *err)
{
    *out = (fc_mesh_data){0};
    fc_mesh_format format = fc_mesh_format_from_path(name);
    if (format == FC_MESH_FILE_UNKNOWN)
        return fc_error_set(err, FC_ERR_USAGE, "%s: not a mesh file this reader knows (.obj, .stl, .ply, .vtk, .vtp)", name);
    fc_cursor c;
    fc_cursor_init(&c, data, size, name);
    fc_mesh_builder b = {0};
    fc_code code;
    switch (format) {
    case FC_MESH_FILE_OBJ: code = fc_read_mesh_obj(&c, &b, err); break;
    case FC_MESH_FILE_STL: code = fc_read_mesh_stl(&c, &b, err); break;
    case FC_MESH_FILE_PLY: code = fc_read_mesh_ply(&c, &b, err); break;
    case FC_MESH_FILE_VTP: code = fc_read_mesh_vtp(&c, &b, err); break;
    default: code = fc_read_mesh_vtk(&c, &b, err); break;
    }
    if (code == FC_OK)
        code = fc_mesh_builder_finish(&b, &c, out, err);
    fc_mesh_builder_free(&b);
    return code;
}

fc_code fc_read_mesh(const char *path, fc_mesh_data *out, fc_error *err)
{
    *out = (fc_mesh_data){0};
    if (fc_mesh_format_from_path(path) == FC_MESH_FILE_UNKNOWN)
        return fc_error_set(err, FC_ERR_USAGE, "%s: not a mesh file this reader knows (.obj, .stl, .ply, .vtk, .vtp)", path);
    uint8_t *data = NULL;
    size_t size = 0;
    fc_code code = fc_read_file(path, SIZE_MAX, &data, &size, err);
    if (code != FC_OK)
        return code;
    code = fc_read_mesh_mem(path, data, size, out, err);
    free(data);
    return code;
}
