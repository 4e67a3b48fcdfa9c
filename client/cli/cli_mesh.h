/* cli_mesh.h — `--mesh FILE[:color=R,G,B][:opacity=X][:hide-near]` of
 * `fluidcast snapshot` and `fluidcast render`: mesh files (client/meshes:
 * .obj .stl .ply .vtk .vtp) read here and sent as MESH (PROTOCOL.md section 12),
 * mesh i of the command line as id i + 1. A FILE with a %d conversion
 * (box_%04d.obj) is a per-frame mesh: `render` reads it again for every frame
 * with the frame's number; `snapshot` takes it with number 0. A static FILE
 * may move rigidly instead: `:transforms=PLACEMENTS` names a text file of
 * lines "FRAME m00 m01 m02 m03 m10 m11 m12 m13 m20 m21 m22 m23" (a 3x4
 * matrix, world = M (x, y, z, 1)); before each frame the mesh goes where
 * that frame's line puts it (MESH_TRANSFORM), and stays where it was when the
 * frame has no line. */
#ifndef FC_CLI_MESH_H
#define FC_CLI_MESH_H

#include <stdbool.h>
#include <stdint.h>

#include "fluidcast.h"
#include "fluidcast_types.h"
#include "particle_reader.h"

#define FC_CLI_MAX_MESHES 16
#define FC_CLI_MESH_PATH_MAX 4096

typedef struct fc_cli_mesh {
    char path[FC_CLI_MESH_PATH_MAX];   /* a file, or a %d pattern (per_frame) */
    bool per_frame;
    float color[3];                    /* linear RGB, default 0.8 grey */
    float opacity;                     /* default 1: opaque; below 1 glass */
    bool hide_near;                    /* faces turned toward the camera are not drawn (a tank's near walls) */
    char transforms[FC_CLI_MESH_PATH_MAX];   /* a static mesh's placement per frame ("" none): lines
                                                "FRAME m00 m01 m02 m03 m10 .. m23", '#' comments */
} fc_cli_mesh;

/* One --mesh value: the options after the path, each introduced by ':'
 * (read from the right, so a path may hold ':' itself). FC_ERR_USAGE naming
 * the option for an unknown one or a value out of [0, 1]. */
fc_code fc_cli_mesh_parse(const char *value, fc_cli_mesh *out, fc_error *err);

/* Reads and sends the meshes: the static ones when `frame` is NULL, the
 * per-frame ones (with *frame put into their pattern) otherwise; snapshot
 * sends both with frame 0; a static mesh with placements moves to the
 * frame's. When the particles were recentred (`recentring`, may be NULL) every
 * placement moves by the same offset, so the meshes stay where the fluid is
 * (their float32 vertices keep what precision the file gave them). FC_ERR_PARSE / FC_ERR_IO / FC_ERR_LIMIT naming the
 * file for a mesh file that cannot be read; the client's errors otherwise. */
fc_code fc_cli_meshes_send(fc_client *client, const fc_cli_mesh *meshes, int count, const uint32_t *frame,
                           const fc_recentring *recentring, fc_error *err);

/* The exit status for an error of fc_cli_meshes_send: the input's (a mesh
 * file that cannot be read or sent as it is) or the connection's. */
int fc_cli_mesh_exit(fc_code code);

#endif
