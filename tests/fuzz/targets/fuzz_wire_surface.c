/* fuzz_wire_surface.c — libFuzzer target for the surface messages (SURFACE 25,
 * SURFACE_PART 26, wire_surface.h): the input is a byte stream of messages, read
 * by fuzz_read_messages (fuzz_stream.h); its SURFACE_PARTs are replies one after
 * the other, fed in order to an fc_surface_assembly as a client receives them.
 *
 * After a refused part the assembly takes no more; a complete reply either
 * finishes into a mesh that passes fc_surface_mesh_validate, whose part 0
 * re-encodes to the very bytes received (a one-part reply: payloads here are at
 * most 1 MiB), or is refused with INVALID_VALUE; the next part then begins a new
 * reply. A decoded SURFACE re-encodes to the bytes received. */
#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_check.h"
#include "fuzz_stream.h"
#include "wire.h"
#include "wire_surface.h"

/* The reply of the current input: the harness's state between its messages. */
typedef struct reply_state {
    fc_surface_assembly assembly;
    bool failed;
    uint8_t *first;          /* part 0's payload, to compare with the re-encoded mesh */
    size_t first_size;
} reply_state;

static reply_state reply;

static void reply_reset(void)
{
    fc_surface_assembly_free(&reply.assembly);
    free(reply.first);
    memset(&reply, 0, sizeof reply);
    fc_surface_assembly_init(&reply.assembly, 0);
}

static void check_finished_mesh(const fc_surface_mesh *m, float extract_ms)
{
    fc_error check = {FC_OK, ""};
    FUZZ_REQUIRE(fc_surface_mesh_validate(m, &check) == FC_OK, "finished mesh is invalid: %s", check.message);
    FUZZ_REQUIRE(fc_surface_part_count(fc_surface_body_size(m->vertex_count, m->triangle_count, m->attributes)) == 1,
                 "a payload under 1 MiB finished a reply of several parts");
    fc_buf encoded;
    fc_buf_init(&encoded);
    FUZZ_REQUIRE(fc_wire_write_surface_part(&encoded, 0, m, extract_ms, 0, &check) == FC_OK, "re-encoding failed: %s",
                 check.message);
    /* extract_ms travels as a float's bytes, NaN payloads included: compared as they came. */
    if (!encoded.failed && encoded.len == FC_WIRE_HEADER_SIZE + reply.first_size)
        memcpy(encoded.data + FC_WIRE_HEADER_SIZE + 20, reply.first + 20, 4);
    fuzz_require_same_payload(&encoded, (fuzz_payload){reply.first, reply.first_size});
    fc_buf_free(&encoded);
}

static fc_code finish(fc_error *err)
{
    fc_surface_mesh m;
    float extract_ms = 0;
    fc_code code = fc_surface_assembly_finish(&reply.assembly, &m, &extract_ms, err);
    if (code != FC_OK) {
        FUZZ_REQUIRE(code == FC_ERR_INVALID_VALUE, "a complete reply refused with %d: %s", (int)code, err->message);
        FUZZ_REQUIRE(m.positions == NULL && m.vertex_count == 0, "a refused reply left a mesh behind");
    } else {
        check_finished_mesh(&m, extract_ms);
        fc_surface_mesh_free(&m);
    }
    reply_reset();   /* the next part begins another reply */
    return code;
}

static fc_code decode_part(fuzz_payload in, fc_error *err)
{
    bool was_failed = reply.failed;
    if (reply.assembly.next_index == 0 && !was_failed) {
        free(reply.first);
        reply.first = malloc(in.n ? in.n : 1);
        memcpy(reply.first, in.p, in.n);
        reply.first_size = in.n;
    }
    bool complete = false;
    fc_code code = fc_surface_assembly_add(&reply.assembly, in.p, in.n, &complete, err);
    FUZZ_REQUIRE(!was_failed || code != FC_OK, "a part was taken after the reply failed");
    if (code != FC_OK) {
        FUZZ_REQUIRE(!complete, "a refused part completed the reply");
        reply.failed = true;
        /* INCONSISTENT is the receiver's own verdict on a later part (PROTOCOL.md 13.3); the
         * stream harness knows the codes a server answers a payload with. */
        return code == FC_ERR_INCONSISTENT ? FC_ERR_MALFORMED : code;
    }
    return complete ? finish(err) : FC_OK;
}

static fc_code decode_request(fuzz_payload in, fc_error *err)
{
    uint32_t attributes = 0;
    fc_code code = fc_wire_read_surface_request(in.p, in.n, &attributes, err);
    if (code != FC_OK)
        return code;
    FUZZ_REQUIRE((attributes & ~FC_SURFACE_ATTRIBUTES_ALL) == 0, "attributes 0x%x", (unsigned)attributes);
    fc_error check = {FC_OK, ""};
    fc_buf encoded;
    fc_buf_init(&encoded);
    FUZZ_REQUIRE(fc_wire_write_surface_request(&encoded, 0, attributes, &check) == FC_OK, "re-encoding failed: %s",
                 check.message);
    fuzz_require_same_payload(&encoded, in);
    fc_buf_free(&encoded);
    return FC_OK;
}

static fc_code decode_payload(uint16_t type, fuzz_payload in, fc_error *err)
{
    switch (type) {
    case FC_MSG_SURFACE: return decode_request(in, err);
    case FC_MSG_SURFACE_PART: return decode_part(in, err);
    }
    return FC_OK; /* other messages have targets of their own */
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    reply_reset();
    fuzz_read_messages(data, size, decode_payload);
    reply_reset();
    return 0;
}
