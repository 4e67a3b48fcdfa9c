/* test_soak_shutdown.c — graceful shutdown under load: several clients have
 * RENDERs queued or rendering in the real fluidcastd when it gets SIGTERM.
 * Each must still be answered (here: with its image, since nothing is wrong
 * with the requests), the connections then close, and the daemon exits 0. */
#include <signal.h>
#include <stdio.h>
#include <unistd.h>

#include "fc_error.h"
#include "service_support.h"
#include "support/test_scene.h"
#include "test_util.h"

enum {
    CLIENTS = 6,
    /* Large enough that llvmpipe is still busy with the queue when SIGTERM arrives. */
    SIZE = 192,
    /* Lets the daemon read every request before the signal: reading is fast, rendering is not. */
    SETTLE_MS = 150,
    FIRST_ID = 10
};

/* Connects, handshakes and sends FRAME, CAMERA and RENDER without waiting for the reply. */
static int send_render(const fc_test_daemon *d, int client)
{
    int fd = -1;
    fc_welcome welcome;
    fc_error err;
    fc_render_request request = {.format = FC_FORMAT_PNG, .quality = 90, .aov = FC_AOV_COLOR};
    fc_buf out;
    fc_buf_init(&out);
    bool sent = fc_test_connect(d->port, &fd, &err) == FC_OK && fc_test_handshake(fd, 1, &welcome, &err) == FC_OK &&
                fc_test_write_render_sequence(&out, FIRST_ID, SIZE, SIZE, &request, &err) == FC_OK &&
                fc_test_send(fd, out.data, out.len, &err) == FC_OK;
    fc_buf_free(&out);
    CHECK_MSG(sent, "client %d: %s", client, err.message);
    return fd;
}

/* The one reply must be the IMAGE answering the RENDER; then the daemon closes. */
static void expect_answer_then_close(int fd, int client)
{
    fc_test_message reply = {0};
    fc_image_reply image;
    fc_error err;
    fc_code code = fc_test_read_message(fd, FC_TEST_IO_TIMEOUT_MS, &reply, &err);
    CHECK_MSG(code == FC_OK, "client %d got no answer: %s", client, err.message);
    if (code == FC_OK) {
        CHECK_MSG(reply.header.type == FC_MSG_IMAGE, "client %d: message type %d", client, (int)reply.header.type);
        CHECK_CODE(reply.header.request_id, FIRST_ID + 2);
        bool decoded = fc_wire_read_image(reply.payload, reply.header.length, &image, &err) == FC_OK;
        CHECK_MSG(decoded && image.width == SIZE && image.height == SIZE && image.format == FC_FORMAT_PNG &&
                      image.size > 8,
                  "client %d: image reply not as requested", client);
    }
    fc_test_message_free(&reply);
    CHECK_MSG(fc_test_expect_closed(fd, FC_TEST_IO_TIMEOUT_MS, &err) == FC_OK, "client %d: %s", client,
              err.message);
}

int main(void)
{
    fc_test_daemon daemon;
    svc_start_daemon(&daemon, NULL);
    int fds[CLIENTS];
    for (int i = 0; i < CLIENTS; i++)
        fds[i] = send_render(&daemon, i);
    svc_sleep_ms(SETTLE_MS);
    CHECK(kill(daemon.pid, SIGTERM) == 0);
    for (int i = 0; i < CLIENTS; i++) {
        if (fds[i] >= 0)
            expect_answer_then_close(fds[i], i);
        close(fds[i]);
    }
    /* The daemon is exiting already: this only collects its status (and kills it if it hangs). */
    CHECK_MSG(svc_stop_daemon(&daemon), "fluidcastd did not exit 0 after SIGTERM");
    return test_result();
}
