/* fuzz_mesh_reader.c — libFuzzer target for the mesh readers (client/meshes):
 * the input is a whole mesh file, read with fc_read_mesh_mem under the name
 * FUZZ_FILE_NAME, whose extension picks the reader (one target per format).
 * A refusal is FC_ERR_PARSE or FC_ERR_LIMIT naming the file and leaves no
 * arrays; an accepted mesh has triangles, every index below its vertex count
 * and finite coordinates, and is one MESH would carry (fc_mesh_validate). */
#include <stdint.h>
#include <string.h>

#include "fuzz_check.h"
#include "mesh_reader.h"
#include "wire_mesh.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fc_mesh_data m;
    fc_error err = {FC_OK, ""};
    fc_code code = fc_read_mesh_mem(FUZZ_FILE_NAME, data, size, &m, &err);
    if (code != FC_OK) {
        FUZZ_REQUIRE(code == FC_ERR_PARSE || code == FC_ERR_LIMIT || code == FC_ERR_NOMEM, "refused with code %d: %s",
                     (int)code, err.message);
        FUZZ_REQUIRE(strstr(err.message, FUZZ_FILE_NAME) != NULL, "the message does not name the file: %s",
                     err.message);
        FUZZ_REQUIRE(m.vertices == NULL && m.indices == NULL, "a refused read left arrays");
        return 0;
    }
    fc_mesh mesh = {.vertex_count = m.vertex_count, .triangle_count = m.triangle_count, .vertices = m.vertices,
                    .indices = m.indices, .color = {1, 1, 1}, .opacity = 1};
    fc_mesh_identity(mesh.transform);
    fc_error check = {FC_OK, ""};
    FUZZ_REQUIRE(m.triangle_count > 0 && fc_mesh_validate(&mesh, &check) == FC_OK, "the mesh read is invalid: %s",
                 check.message);
    fc_mesh_data_free(&m);
    return 0;
}
