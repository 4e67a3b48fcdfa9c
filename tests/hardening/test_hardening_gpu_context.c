/* test_hardening_gpu_context.c — a lost GPU context, against the real
 * fluidcastd. llvmpipe never loses one, so the daemon's test hook
 * FLUIDCASTD_TEST_LOSE_CONTEXT makes one render report a reset; from there on
 * the real recovery runs (context and pipeline destroyed and created again).
 *
 * The requester gets ERROR RENDER saying the context was lost; a render asked
 * for at the same time is served; the requester's next render is right; and
 * a client whose frame and background image were uploaded before the loss
 * renders again without sending either, to the same pixels as before. */
#include <string.h>
#include <unistd.h>

#include "hardening_harness.h"
#include "test_util.h"

/* Renders that reach the GPU, in the order this test makes them: 1 the
 * witness at startup, 2 and 3 the background client, 4 and 5 the two clients
 * asking at once. */
#define LOST_RENDER "4"

int main(void)
{
    static const char *const environment[] = {"FLUIDCASTD_TEST_LOSE_CONTEXT=" LOST_RENDER, NULL};
    fc_test_daemon_setup setup = {.environment = environment};
    hx_env env;
    if (!hx_env_start_with(&env, &setup))
        return hx_exit_status(1);

    /* Renders 2 and 3: a client with its own background, uploaded before the loss. */
    int scenic = hx_connect_greeted(&env, 0);
    fc_buf before, after;
    fc_buf_init(&before);
    fc_buf_init(&after);
    fc_buf out;
    fc_buf_init(&out);
    hx_send_magenta_background(scenic, 20);
    hx_write_render_sequence(&out, 21);
    hx_send_buf(scenic, &out);
    hx_send_render(scenic, 24, FC_FORMAT_RAW, FC_AOV_COLOR);
    hx_expect_cube_image(scenic, 23);
    hx_expect_magenta_image(scenic, 24, &before);

    /* Render 4 loses the context: two clients ask at once, and whichever the
     * daemon takes first is the victim (sockets do not order the arrival of
     * two connections' bytes); the other is served by the context made after. */
    int first = hx_connect_greeted(&env, 0);
    int second = hx_connect_greeted(&env, 0);
    hx_write_render_sequence(&out, 30);
    hx_send_buf(first, &out);
    hx_write_render_sequence(&out, 60);
    hx_send_buf(second, &out);
    static const char lost[] = "GPU context lost (unknown reset)";
    bool first_lost = hx_expect_cube_image_or_error(first, 32, FC_ERR_RENDER, lost);
    bool second_lost = hx_expect_cube_image_or_error(second, 62, FC_ERR_RENDER, lost);
    CHECK_MSG(first_lost != second_lost, "renders lost: first %d, second %d; expected exactly one", first_lost,
              second_lost);
    /* The victim's next render is right. */
    hx_expect_renders(first_lost ? first : second, 40);
    hx_expect_witness_served(&env);

    /* Only RENDER: the frame and the background come back from the daemon's copies. */
    hx_send_render(scenic, 50, FC_FORMAT_RAW, FC_AOV_COLOR);
    hx_expect_magenta_image(scenic, 50, &after);
    CHECK_MSG(before.len > 0 && before.len == after.len && memcmp(before.data, after.data, before.len) == 0,
              "the background client's image changed across the context loss");

    fc_buf_free(&out);
    fc_buf_free(&before);
    fc_buf_free(&after);
    close(first);
    close(second);
    close(scenic);
    hx_env_stop(&env);
    return hx_exit_status(0);
}
