/* test_daemon_png.c — fluidcastd --png-compression end to end: three daemons
 * (level 0, the default, level 9) render the same cube as PNG; every IMAGE
 * decodes to the same pixels, level 0 stores them (at least their raw size),
 * and each higher level is smaller. Out-of-range levels: test_daemon_startup. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "daemon_process.h"
#include "fc_error.h"
#include "image_decode.h"
#include "test_scene.h"
#include "test_util.h"

enum { WIDTH = 256, HEIGHT = 192, LEVELS = 3 };

/* The PNG bytes of the cube rendered by a daemon started with `level` (NULL:
 * the default), decoded into *pixels (malloc'd RGB: a colour image is opaque, so
 * the daemon writes it without alpha); its size, 0 on failure. */
static size_t render_png(const char *level, uint8_t **pixels)
{
    const char *args[] = {"--max-image", "256x192", "--png-compression", level, NULL};
    if (!level)
        args[2] = NULL;
    *pixels = NULL;
    fc_test_daemon daemon;
    fc_error err;
    if (fc_test_daemon_start(&daemon, args, FC_TEST_DAEMON_START_TIMEOUT_MS, &err) != FC_OK) {
        CHECK_MSG(0, "--png-compression %s: cannot start the daemon: %s", level ? level : "(default)", err.message);
        return 0;
    }
    size_t size = 0;
    int fd = -1;
    fc_welcome welcome;
    CHECK_CODE(fc_test_connect(daemon.port, &fd, &err), FC_OK);
    if (fd >= 0 && fc_test_handshake(fd, 1, &welcome, &err) == FC_OK) {
        fc_render_request request = {FC_FORMAT_PNG, 0, FC_AOV_COLOR};
        fc_test_message reply = {0};
        fc_image_reply image = {0};
        fc_decoded_image png;
        CHECK_MSG(fc_test_render(fd, 10, WIDTH, HEIGHT, &request, &reply, &err) == FC_OK, "%s", err.message);
        CHECK_MSG(reply.header.type == FC_MSG_IMAGE, "reply type %u", reply.header.type);
        if (reply.header.type == FC_MSG_IMAGE &&
            fc_wire_read_image(reply.payload, reply.header.length, &image, &err) == FC_OK &&
            fc_decode_image(image.data, image.size, "png", 0, &png, &err) == FC_OK) {
            CHECK(png.width == WIDTH && png.height == HEIGHT && png.channels == 3);
            *pixels = malloc((size_t)WIDTH * HEIGHT * 3);
            if (*pixels && png.width == WIDTH && png.height == HEIGHT && png.channels == 3) {
                memcpy(*pixels, png.pixels, (size_t)WIDTH * HEIGHT * 3);
                size = image.size;
            }
            fc_decoded_image_free(&png);
        } else {
            CHECK_MSG(0, "--png-compression %s: no PNG IMAGE: %s", level ? level : "(default)", err.message);
        }
        fc_test_message_free(&reply);
    } else {
        CHECK_MSG(0, "handshake: %s", err.message);
    }
    if (fd >= 0)
        close(fd);
    CHECK_MSG(fc_test_daemon_stop(&daemon, FC_TEST_DAEMON_STOP_TIMEOUT_MS, &err) == FC_OK, "%s", err.message);
    return size;
}

int main(void)
{
    static const char *const levels[LEVELS] = {"0", NULL, "9"};
    uint8_t *pixels[LEVELS];
    size_t sizes[LEVELS];
    for (int i = 0; i < LEVELS; i++)
        sizes[i] = render_png(levels[i], &pixels[i]);
    printf("PNG of %dx%d: %zu bytes at level 0, %zu at the default, %zu at level 9\n", WIDTH, HEIGHT, sizes[0],
           sizes[1], sizes[2]);
    if (sizes[0] && sizes[1] && sizes[2]) {
        /* Lossless at every level: the same image, byte for byte. */
        CHECK_MSG(memcmp(pixels[0], pixels[1], (size_t)WIDTH * HEIGHT * 3) == 0, "level 0 and default differ");
        CHECK_MSG(memcmp(pixels[2], pixels[1], (size_t)WIDTH * HEIGHT * 3) == 0, "level 9 and default differ");
        /* Level 0 stores the rows as they are (plus a filter byte per row and zlib's framing). */
        CHECK_MSG(sizes[0] >= (size_t)WIDTH * HEIGHT * 3, "level 0: %zu bytes for %d raw", sizes[0],
                  WIDTH * HEIGHT * 3);
        CHECK_MSG(sizes[1] < sizes[0] / 2, "default: %zu bytes, level 0: %zu", sizes[1], sizes[0]);
        CHECK_MSG(sizes[2] < sizes[1], "level 9: %zu bytes, default: %zu", sizes[2], sizes[1]);
    }
    for (int i = 0; i < LEVELS; i++)
        free(pixels[i]);
    return test_result();
}
