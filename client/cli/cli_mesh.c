/* cli_mesh.c — see cli_mesh.h. */
#include "cli_mesh.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli_read_options.h"
#include "cli_report.h"
#include "cli_values.h"
#include "fc_error.h"
#include "mesh_reader.h"
#include "render_inputs.h"

/* Parsed as the float it is stored in and checked as that float. */
static fc_code parse_unit(const char *option, const char *text, float *out, fc_error *err)
{
    char *end;
    float v = strtof(text, &end);
    if (end == text || *end != '\0' || !(v >= 0.0f && v <= 1.0f))
        return fc_error_set(err, FC_ERR_USAGE, "--mesh: %s needs a number in [0, 1], not \"%s\"", option, text);
    *out = v;
    return FC_OK;
}

/* One option after a ':'. *known false: not an option (part of the path). */
static fc_code parse_option(const char *text, fc_cli_mesh *m, bool *known, fc_error *err)
{
    *known = true;
    if (strcmp(text, "hide-near") == 0) {
        m->hide_near = true;
        return FC_OK;
    }
    if (strncmp(text, "transforms=", 11) == 0) {
        if (text[11] == '\0' || strlen(text + 11) >= sizeof m->transforms)
            return fc_error_set(err, FC_ERR_USAGE, "--mesh: transforms needs a file");
        snprintf(m->transforms, sizeof m->transforms, "%s", text + 11);
        return FC_OK;
    }
    if (strncmp(text, "opacity=", 8) == 0)
        return parse_unit("opacity", text + 8, &m->opacity, err);
    if (strncmp(text, "color=", 6) == 0) {
        char copy[128];
        snprintf(copy, sizeof copy, "%s", text + 6);
        char *parts[3], *save = NULL;
        int n = 0;
        for (char *p = strtok_r(copy, ",", &save); p && n < 4; p = strtok_r(NULL, ",", &save))
            if (n < 3)
                parts[n++] = p;
            else
                n++;
        if (n != 3)
            return fc_error_set(err, FC_ERR_USAGE, "--mesh: color needs R,G,B (each in [0, 1]), not \"%s\"", text + 6);
        for (int k = 0; k < 3; k++) {
            fc_code code = parse_unit("color", parts[k], &m->color[k], err);
            if (code != FC_OK)
                return code;
        }
        return FC_OK;
    }
    *known = false;
    return FC_OK;
}

fc_code fc_cli_mesh_parse(const char *value, fc_cli_mesh *out, fc_error *err)
{
    *out = (fc_cli_mesh){.color = {0.8f, 0.8f, 0.8f}, .opacity = 1.0f};
    size_t len = strlen(value);
    if (len == 0 || len >= FC_CLI_MESH_PATH_MAX)
        return fc_error_set(err, FC_ERR_USAGE, "--mesh needs a mesh file (.obj .stl .ply .vtk .vtp)");
    char text[FC_CLI_MESH_PATH_MAX];
    memcpy(text, value, len + 1);
    /* Options from the right; the first segment that is none ends them. */
    for (;;) {
        char *colon = strrchr(text, ':');
        if (!colon)
            break;
        bool known;
        fc_code code = parse_option(colon + 1, out, &known, err);
        if (code != FC_OK)
            return code;
        if (!known) {
            if (strchr(colon + 1, '=') || strcmp(colon + 1, "hide_near") == 0)
                return fc_error_set(err, FC_ERR_USAGE,
                                    "--mesh: unknown option \"%s\" (color=R,G,B, opacity=X, hide-near, "
                                    "transforms=FILE)", colon + 1);
            break;
        }
        *colon = '\0';
    }
    snprintf(out->path, sizeof out->path, "%s", text);
    out->per_frame = fc_is_frame_pattern(out->path);
    if (out->per_frame && out->transforms[0])
        return fc_error_set(err, FC_ERR_USAGE, "--mesh: a per-frame file (%s) takes no transforms file", out->path);
    if (!out->per_frame && strchr(out->path, '%'))
        return fc_error_set(err, FC_ERR_USAGE, "--mesh: %s is neither a file nor a pattern with one %%d", out->path);
    if (fc_mesh_format_from_path(out->path) == FC_MESH_FILE_UNKNOWN)
        return fc_error_set(err, FC_ERR_USAGE, "--mesh: %s is not a mesh file this command reads (.obj .stl .ply .vtk .vtp)",
                            out->path);
    return FC_OK;
}

/* The particles were shifted by the recentring's offset: a placement moves likewise (world - offset). */
static void recentre(const fc_recentring *r, float transform[12])
{
    for (int k = 0; r && r->applied && k < 3; k++)
        transform[4 * k + 3] = (float)((double)transform[4 * k + 3] - r->offset[k]);
}

/* The row of `frame` in a transforms file: "FRAME m00 m01 m02 m03 m10 ... m23" per
 * line, '#' comments. *found false when the file has no such row. */
static fc_code find_transform(const char *path, uint32_t frame, float transform[12], bool *found, fc_error *err)
{
    *found = false;
    FILE *f = fopen(path, "r");
    if (!f)
        return fc_error_set(err, FC_ERR_IO, "--mesh transforms: cannot open %s", path);
    char line[1024];
    unsigned number = 0;
    fc_code code = FC_OK;
    while (code == FC_OK && !*found && fgets(line, sizeof line, f)) {
        number++;
        char *p = line + strspn(line, " \t");
        if (*p == '#' || *p == '\n' || *p == '\r' || *p == '\0')
            continue;
        char *end;
        double values[13];
        int n = 0;
        for (; n < 13; n++) {
            values[n] = strtod(p, &end);
            if (end == p)
                break;
            p = end;
        }
        p += strspn(p, " \t\r\n");
        /* The matrix is checked as the floats MESH_TRANSFORM carries: 1e39 is a finite double only. */
        bool finite = true;
        for (int k = 1; k < n; k++)
            finite = finite && isfinite((float)values[k]);
        /* The frame is range-checked before its conversion, which is undefined outside uint32_t's range. */
        bool frame_ok = n > 0 && values[0] >= 0.0 && values[0] <= (double)UINT32_MAX && values[0] == floor(values[0]);
        if (n != 13 || *p != '\0' || !finite || !frame_ok)
            code = fc_error_set(err, FC_ERR_PARSE, "%s: line %u: not \"FRAME\" and 12 finite numbers (a 3x4 matrix)",
                                path, number);
        else if ((uint32_t)values[0] == frame) {
            for (int k = 0; k < 12; k++)
                transform[k] = (float)values[k + 1];
            *found = true;
        }
    }
    fclose(f);
    return code;
}

/* A static mesh with a transforms file goes where its row for `frame` says (no row: it stays). */
static fc_code move_one(fc_client *client, const fc_cli_mesh *m, uint32_t id, uint32_t frame,
                        const fc_recentring *recentring, fc_error *err)
{
    fc_mesh_transform entry = {.id = id};
    bool found;
    fc_code code = find_transform(m->transforms, frame, entry.transform, &found, err);
    if (code != FC_OK || !found)
        return code;
    recentre(recentring, entry.transform);
    return fc_client_move_meshes(client, &entry, 1, err);
}

static fc_code send_one(fc_client *client, const fc_cli_mesh *m, uint32_t id, const char *path,
                        const fc_recentring *recentring, fc_error *err)
{
    fc_mesh_data data;
    fc_code code = fc_read_mesh(path, &data, err);
    if (code != FC_OK)
        return code;
    fc_mesh mesh;
    fc_mesh_defaults(&mesh);
    recentre(recentring, mesh.transform);
    mesh.id = id;
    mesh.flags = m->hide_near ? FC_MESH_HIDE_NEAR : 0;
    mesh.vertex_count = data.vertex_count;
    mesh.triangle_count = data.triangle_count;
    mesh.vertices = data.vertices;
    mesh.indices = data.indices;
    memcpy(mesh.color, m->color, sizeof mesh.color);
    mesh.opacity = m->opacity;
    code = fc_client_upload_mesh(client, &mesh, err);
    fc_mesh_data_free(&data);
    return code;
}

fc_code fc_cli_meshes_send(fc_client *client, const fc_cli_mesh *meshes, int count, const uint32_t *frame,
                           const fc_recentring *recentring, fc_error *err)
{
    for (int i = 0; i < count; i++) {
        const fc_cli_mesh *m = &meshes[i];
        if (frame && !m->per_frame && m->transforms[0]) {
            fc_code code = move_one(client, m, (uint32_t)i + 1, *frame, recentring, err);
            if (code != FC_OK)
                return code;
            continue;
        }
        if (m->per_frame != (frame != NULL))
            continue;
        char path[FC_CLI_MESH_PATH_MAX];
        fc_code code = FC_OK;
        if (m->per_frame)
            code = fc_pattern_path(m->path, *frame, path, sizeof path, err);
        else
            snprintf(path, sizeof path, "%s", m->path);
        if (code == FC_OK)
            code = send_one(client, m, (uint32_t)i + 1, path, recentring, err);
        if (code != FC_OK)
            return code;
    }
    return FC_OK;
}

int fc_cli_mesh_exit(fc_code code)
{
    switch (code) {
    case FC_ERR_PARSE:
    case FC_ERR_IO:
    case FC_ERR_LIMIT:
    case FC_ERR_INVALID_VALUE:
    case FC_ERR_USAGE:
    case FC_ERR_TOO_LARGE:
        return FC_EXIT_INPUT;
    default:
        return fc_cli_exit_for_client_error(code);
    }
}
