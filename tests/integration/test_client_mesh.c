/* test_client_mesh.c — libfluidcast's meshes against the real fluidcastd
 * (PROTOCOL.md section 12): fc_client_upload_mesh, fc_client_remove_mesh and
 * fc_client_move_meshes. What the library can check (an index past the
 * vertices, a NaN vertex, counts beyond the limits) fails at once and sends
 * nothing; what only the server knows (a mesh never sent, a 65th mesh, the
 * memory limit) is reported by the next render with the server's code, and
 * the connection renders on. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "fluidcast.h"
#include "support/daemon_process.h"
#include "test_ball.h"
#include "test_util.h"

#define SIDE 32

/* 2 MB per connection: the ball and a few small meshes fit, 100000 vertices with normals do not. */
static const char *const daemon_args[] = {"--max-session-memory", "2000000", NULL};

static fc_code send_ball(fc_client *client, fc_error *err)
{
    fc_frame ball = {0};
    fc_code code = test_ball_frame(&ball, err);
    if (code == FC_OK)
        code = fc_client_send_frame(client, &ball, err);
    fc_frame_free(&ball);
    fc_camera cam;
    test_ball_camera(SIDE, SIDE, &cam);
    if (code == FC_OK)
        code = fc_client_set_camera(client, &cam, err);
    return code;
}

/* A render of the depth AOV: FC_OK, or the error the server reported for an earlier message. */
static fc_code render(fc_client *client, fc_error *err)
{
    fc_render_request request = {.format = FC_FORMAT_RAW, .quality = 0, .aov = FC_AOV_DEPTH};
    fc_image_result image;
    fc_code code = fc_client_render(client, &request, &image, err);
    fc_image_result_free(&image);
    return code;
}

/* A fan of n vertices on a circle far below the ball (z = -50), normals up when asked. */
typedef struct fan {
    float *vertices, *normals;
    uint32_t *indices;
    fc_mesh mesh;
} fan;

static void fan_make(fan *f, uint32_t id, uint32_t n, bool normals)
{
    f->vertices = malloc(12 * (size_t)n);
    f->normals = normals ? malloc(12 * (size_t)n) : NULL;
    f->indices = malloc(12 * (size_t)(n - 2));
    for (uint32_t i = 0; i < n; i++) {
        double a = 2 * 3.14159265358979 * i / n;
        f->vertices[3 * i] = (float)cos(a);
        f->vertices[3 * i + 1] = (float)sin(a);
        f->vertices[3 * i + 2] = 0;
        if (normals)
            memcpy(f->normals + 3 * i, (float[3]){0, 0, 1}, 12);
    }
    for (uint32_t t = 0; t + 2 < n; t++) {
        f->indices[3 * t] = 0;
        f->indices[3 * t + 1] = t + 1;
        f->indices[3 * t + 2] = t + 2;
    }
    fc_mesh_defaults(&f->mesh);
    f->mesh.id = id;
    f->mesh.vertex_count = n;
    f->mesh.triangle_count = n - 2;
    f->mesh.vertices = f->vertices;
    f->mesh.indices = f->indices;
    f->mesh.normals = f->normals;
    f->mesh.transform[11] = -50.0f;
}

static void fan_free(fan *f)
{
    free(f->vertices);
    free(f->normals);
    free(f->indices);
}

static void test_upload_move_remove(fc_client *client)
{
    fc_error err;
    fan a, b;
    fan_make(&a, 1, 16, true);
    fan_make(&b, 2, 5, false);
    CHECK_CODE(fc_client_upload_mesh(client, &a.mesh, &err), FC_OK);
    CHECK_CODE(fc_client_upload_mesh(client, &b.mesh, &err), FC_OK);
    CHECK_CODE(render(client, &err), FC_OK);

    fc_mesh_transform moves[2] = {{.id = 2}, {.id = 1}};
    memcpy(moves[0].transform, a.mesh.transform, sizeof moves[0].transform);
    memcpy(moves[1].transform, a.mesh.transform, sizeof moves[1].transform);
    moves[1].transform[3] = 3.0f;
    CHECK_CODE(fc_client_move_meshes(client, moves, 2, &err), FC_OK);
    CHECK_CODE(render(client, &err), FC_OK);

    /* Mesh 3 was never sent: nothing moves, the render reports BAD_STATE naming it. */
    moves[1].id = 3;
    CHECK_CODE(fc_client_move_meshes(client, moves, 2, &err), FC_OK);
    CHECK_CODE(render(client, &err), FC_ERR_BAD_STATE);
    CHECK_MSG(strstr(err.message, "no mesh 3") != NULL, "%s", err.message);
    CHECK_CODE(render(client, &err), FC_OK);

    /* Removed, mesh 2 cannot be moved any more; removing it again is no error. */
    CHECK_CODE(fc_client_remove_mesh(client, 2, &err), FC_OK);
    CHECK_CODE(fc_client_remove_mesh(client, 2, &err), FC_OK);
    CHECK_CODE(render(client, &err), FC_OK);
    CHECK_CODE(fc_client_move_meshes(client, moves, 1, &err), FC_OK);
    CHECK_CODE(render(client, &err), FC_ERR_BAD_STATE);
    CHECK_CODE(fc_client_remove_mesh(client, 1, &err), FC_OK);
    CHECK_CODE(render(client, &err), FC_OK);
    fan_free(&a);
    fan_free(&b);
}

/* Refused by the library before sending: the connection is untouched. */
static void test_local_refusals(fc_client *client)
{
    fc_error err;
    fan f;
    fan_make(&f, 5, 6, false);
    f.indices[3 * 3 + 1] = 6; /* triangle 3 refers to vertex 6 of 6 */
    CHECK_CODE(fc_client_upload_mesh(client, &f.mesh, &err), FC_ERR_INVALID_VALUE);
    CHECK_MSG(strstr(err.message, "triangle 3 refers to vertex 6") != NULL, "%s", err.message);
    f.indices[3 * 3 + 1] = 4;
    f.vertices[7] = NAN;
    CHECK_CODE(fc_client_upload_mesh(client, &f.mesh, &err), FC_ERR_INVALID_VALUE);
    CHECK_MSG(strstr(err.message, "vertex 2") != NULL, "%s", err.message);
    f.vertices[7] = 0;
    f.mesh.opacity = 2.0f;
    CHECK_CODE(fc_client_upload_mesh(client, &f.mesh, &err), FC_ERR_INVALID_VALUE);
    f.mesh.opacity = 1.0f;
    f.mesh.vertex_count = (1u << 24) + 1;
    CHECK_CODE(fc_client_upload_mesh(client, &f.mesh, &err), FC_ERR_LIMIT);
    CHECK_CODE(fc_client_upload_mesh(client, NULL, &err), FC_ERR_USAGE);
    fc_mesh_transform too_many[65] = {{0}};
    CHECK_CODE(fc_client_move_meshes(client, too_many, 65, &err), FC_ERR_LIMIT);
    CHECK_CODE(render(client, &err), FC_OK);
    fan_free(&f);
}

/* Refused by the server: the limits it alone can see. */
static void test_server_limits(fc_client *client)
{
    fc_error err;
    fan big;
    fan_make(&big, 9, 100000, true);
    CHECK_CODE(fc_client_upload_mesh(client, &big.mesh, &err), FC_OK);
    CHECK_CODE(render(client, &err), FC_ERR_LIMIT);
    CHECK_MSG(strstr(err.message, "max_session_memory") != NULL, "%s", err.message);
    fan_free(&big);

    fan small;
    fan_make(&small, 0, 3, false);
    for (uint32_t id = 100; id < 164; id++) {
        small.mesh.id = id;
        CHECK_CODE(fc_client_upload_mesh(client, &small.mesh, &err), FC_OK);
    }
    CHECK_CODE(render(client, &err), FC_OK);
    small.mesh.id = 99;
    CHECK_CODE(fc_client_upload_mesh(client, &small.mesh, &err), FC_OK);
    CHECK_CODE(render(client, &err), FC_ERR_LIMIT);
    /* Room again after a removal. */
    CHECK_CODE(fc_client_remove_mesh(client, 100, &err), FC_OK);
    CHECK_CODE(fc_client_upload_mesh(client, &small.mesh, &err), FC_OK);
    CHECK_CODE(render(client, &err), FC_OK);
    fan_free(&small);
}

int main(void)
{
    fc_test_daemon daemon;
    fc_error err;
    if (fc_test_daemon_start(&daemon, daemon_args, FC_TEST_DAEMON_START_TIMEOUT_MS, &err) != FC_OK) {
        fprintf(stderr, "cannot start fluidcastd: %s\n", err.message);
        return 1;
    }
    char address[32];
    snprintf(address, sizeof address, "127.0.0.1:%u", (unsigned)daemon.port);
    fc_client *client = NULL;
    CHECK_CODE(fc_client_connect(address, NULL, &client, &err), FC_OK);
    if (client && send_ball(client, &err) == FC_OK) {
        test_upload_move_remove(client);
        test_local_refusals(client);
        test_server_limits(client);
    }
    fc_client_close(client);
    CHECK_CODE(fc_test_daemon_stop(&daemon, FC_TEST_DAEMON_STOP_TIMEOUT_MS, &err), FC_OK);
    return test_result();
}
