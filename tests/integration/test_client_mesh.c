/* test_client_mesh.c — libfluidcast's meshes against the real fluidcastd
 * (PROTOCOL.md section 12): fc_client_upload_mesh, fc_client_remove_mesh and
 * fc_client_move_meshes. What the library can check (an index past the
 * vertices, a NaN vertex, counts beyond the limits) fails at once and sends
 * nothing; what only the server knows (a mesh never sent, a 65th mesh, the
 * memory limit) is reported by the next render with the server's code, and
 * the connection renders on. Through the renderer: a box in front of the
 * ball makes its depth AOV 0 at the centre, and moved aside (MESH_TRANSFORM)
 * gives the ball back; a producer's box shows in a viewer's stream images. */
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

static void fc_mesh_identity_for_test(float m[12])
{
    static const float identity[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    memcpy(m, identity, sizeof identity);
}

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

/* The depth AOV's value at the image's centre (0: no fluid), or -1 when the render failed. */
static float centre_depth(fc_client *client, fc_error *err)
{
    fc_render_request request = {.format = FC_FORMAT_RAW, .quality = 0, .aov = FC_AOV_DEPTH};
    fc_image_result image;
    float depth = -1.0f;
    if (fc_client_render(client, &request, &image, err) == FC_OK && image.size == 4u * SIDE * SIDE)
        memcpy(&depth, image.data + 4 * ((SIDE / 2) * SIDE + SIDE / 2), 4);
    fc_image_result_free(&image);
    return depth;
}

/* A box x, z in [-1, 1], y in [-2, -1.8]: test_ball_camera looks along +y from
 * y = -4 at the ball (radius 0.5 about the origin), so the box stands between. */
static const float box_vertices[24] = {-1, -2, -1, 1, -2, -1, -1, -1.8f, -1, 1, -1.8f, -1,
                                       -1, -2, 1,  1, -2, 1,  -1, -1.8f, 1,  1, -1.8f, 1};
static const uint32_t box_indices[36] = {0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6, 0, 1, 5, 0, 5, 4,
                                         2, 6, 7, 2, 7, 3, 0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5};

static fc_mesh box_mesh(uint32_t id)
{
    fc_mesh m;
    fc_mesh_defaults(&m);
    m.id = id;
    m.vertex_count = 8;
    m.triangle_count = 12;
    m.vertices = box_vertices;
    m.indices = box_indices;
    return m;
}

static void test_box_hides_ball(fc_client *client)
{
    fc_error err;
    float plain = centre_depth(client, &err);
    CHECK_MSG(plain > 0.0f, "the ball's centre depth %g", (double)plain);
    fc_mesh box = box_mesh(20);
    CHECK_CODE(fc_client_upload_mesh(client, &box, &err), FC_OK);
    float hidden = centre_depth(client, &err);
    CHECK_MSG(hidden == 0.0f, "behind the box the depth is %g", (double)hidden);
    fc_mesh_transform aside = {.id = 20};
    fc_mesh_identity_for_test(aside.transform);
    aside.transform[3] = 5.0f;   /* 5 units to the side */
    CHECK_CODE(fc_client_move_meshes(client, &aside, 1, &err), FC_OK);
    float back = centre_depth(client, &err);
    CHECK_MSG(fabsf(back - plain) < 1e-4f, "moved aside, the depth is %g, not %g", (double)back, (double)plain);
    CHECK_CODE(fc_client_remove_mesh(client, 20, &err), FC_OK);
    printf("box: centre depth %.3f, behind the box %.3f, box moved aside %.3f\n", (double)plain, (double)hidden,
           (double)back);
}

/* A producer's mesh is its session's: the viewer's stream image shows it. */
static void test_session_mesh(const char *address)
{
    fc_error err;
    fc_client *producer = NULL, *viewer = NULL;
    CHECK_CODE(fc_client_connect(address, NULL, &producer, &err), FC_OK);
    CHECK_CODE(fc_client_connect(address, NULL, &viewer, &err), FC_OK);
    if (!producer || !viewer) {
        fc_client_close(producer);
        fc_client_close(viewer);
        return;
    }
    CHECK_CODE(fc_client_publish(producer, "tank", NULL, &err), FC_OK);
    fc_render_request depth = {.format = FC_FORMAT_RAW, .quality = 0, .aov = FC_AOV_DEPTH};
    CHECK_CODE(fc_client_subscribe(viewer, "tank", &depth, SIDE, SIDE, NULL, &err), FC_OK);
    fc_camera cam;
    test_ball_camera(SIDE, SIDE, &cam);
    CHECK_CODE(fc_client_set_camera(viewer, &cam, &err), FC_OK);
    /* A round trip: the viewer's CAMERA is in before the frame is published, so its first image uses it. */
    fc_session_status *sessions = NULL;
    uint32_t session_count = 0;
    CHECK_CODE(fc_client_list_sessions(viewer, &sessions, &session_count, &err), FC_OK);
    fc_session_list_free(sessions);
    fc_mesh box = box_mesh(1);
    CHECK_CODE(fc_client_upload_mesh(producer, &box, &err), FC_OK);
    fc_frame ball = {0};
    CHECK_CODE(test_ball_frame(&ball, &err), FC_OK);
    CHECK_CODE(fc_client_send_frame(producer, &ball, &err), FC_OK);
    fc_frame_free(&ball);
    /* The first image of the frame (a view-change image may come first: take the last). */
    float centre = -1.0f;
    for (int i = 0; i < 4; i++) {
        fc_stream_image img;
        if (fc_client_next_image(viewer, &img, &err) != FC_OK) {
            CHECK_MSG(0, "stream image: %s", err.message);
            break;
        }
        bool frame_image = img.frame_number == 1 && img.image.size == 4u * SIDE * SIDE;
        if (frame_image)
            memcpy(&centre, img.image.data + 4 * ((SIDE / 2) * SIDE + SIDE / 2), 4);
        fc_stream_image_free(&img);
        if (frame_image)
            break;
    }
    CHECK_MSG(centre == 0.0f, "the viewer sees the producer's box? centre depth %g", (double)centre);
    printf("session: the viewer's centre depth behind the producer's box %.3f\n", (double)centre);
    fc_client_close(producer);
    fc_client_close(viewer);
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
        test_box_hides_ball(client);
        test_server_limits(client);
    }
    fc_client_close(client);
    test_session_mesh(address);
    CHECK_CODE(fc_test_daemon_stop(&daemon, FC_TEST_DAEMON_STOP_TIMEOUT_MS, &err), FC_OK);
    return test_result();
}
