/* fuzz_wire_mesh.c — libFuzzer target for the mesh messages (MESH 12,
 * MESH_TRANSFORM 13, wire_mesh.h): the input is a byte stream of messages as
 * a client would send them, read by fuzz_read_messages (fuzz_stream.h).
 *
 * A decoded MESH passes fc_mesh_validate (every index below V, every vertex
 * and normal finite), owns arrays exactly when it has triangles, and re-encodes
 * to the very bytes received; a decoded MESH_TRANSFORM likewise. */
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>

#include "fuzz_check.h"
#include "fuzz_stream.h"
#include "wire.h"
#include "wire_mesh.h"

static fc_code decode_mesh(fuzz_payload in, fc_error *err)
{
    fc_mesh m;
    void *storage = NULL;
    fc_code code = fc_wire_read_mesh(in.p, in.n, &m, &storage, err);
    if (code != FC_OK) {
        FUZZ_REQUIRE(storage == NULL, "a refused MESH left storage behind");
        return code;
    }
    fc_error check = {FC_OK, ""};
    FUZZ_REQUIRE(fc_mesh_validate(&m, &check) == FC_OK, "decoded mesh is invalid: %s", check.message);
    FUZZ_REQUIRE((storage != NULL) == (m.triangle_count > 0), "storage %p for %u triangles", storage,
                 (unsigned)m.triangle_count);
    uint32_t wire_flags = fuzz_load_u32(in.p + 4);
    /* A removal announcing normals (of its zero vertices) is the one non-canonical form. */
    if (!(m.vertex_count == 0 && (wire_flags & FC_MESH_WIRE_NORMALS))) {
        fc_buf encoded;
        fc_buf_init(&encoded);
        FUZZ_REQUIRE(fc_wire_write_mesh(&encoded, 0, &m, &check) == FC_OK, "re-encoding failed: %s", check.message);
        fuzz_require_same_payload(&encoded, in);
        fc_buf_free(&encoded);
    }
    free(storage);
    return FC_OK;
}

static fc_code decode_transforms(fuzz_payload in, fc_error *err)
{
    fc_mesh_transform entries[FC_MESH_MAX_COUNT];
    uint32_t count = 0;
    fc_code code = fc_wire_read_mesh_transforms(in.p, in.n, entries, &count, err);
    if (code != FC_OK)
        return code;
    FUZZ_REQUIRE(count <= FC_MESH_MAX_COUNT, "%u entries", (unsigned)count);
    fc_error check = {FC_OK, ""};
    fc_buf encoded;
    fc_buf_init(&encoded);
    FUZZ_REQUIRE(fc_wire_write_mesh_transforms(&encoded, 0, entries, count, &check) == FC_OK,
                 "re-encoding failed: %s", check.message);
    fuzz_require_same_payload(&encoded, in);
    fc_buf_free(&encoded);
    return FC_OK;
}

static fc_code decode_payload(uint16_t type, fuzz_payload in, fc_error *err)
{
    switch (type) {
    case FC_MSG_MESH: return decode_mesh(in, err);
    case FC_MSG_MESH_TRANSFORM: return decode_transforms(in, err);
    }
    return FC_OK; /* other messages have targets of their own */
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fuzz_read_messages(data, size, decode_payload);
    return 0;
}
