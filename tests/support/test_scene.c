/* test_scene.c — the cube scene and a one-shot render client. */
#include "test_scene.h"

#include "fc_error.h"
#include "fc_frame.h"

fc_code fc_test_cube_frame(fc_frame *frame, fc_error *err)
{
    const int side = FC_TEST_CUBE_SIDE;
    fc_code code = fc_frame_alloc(frame, (uint64_t)side * side * side, 0, err);
    if (code != FC_OK)
        return code;
    float offset = (side - 1) * FC_TEST_CUBE_SPACING / 2.0f;
    float *p = frame->positions;
    for (int z = 0; z < side; z++)
        for (int y = 0; y < side; y++)
            for (int x = 0; x < side; x++) {
                *p++ = x * FC_TEST_CUBE_SPACING - offset;
                *p++ = y * FC_TEST_CUBE_SPACING - offset;
                *p++ = z * FC_TEST_CUBE_SPACING - offset;
            }
    return FC_OK;
}

void fc_test_front_camera(uint32_t width, uint32_t height, fc_camera *camera)
{
    *camera = (fc_camera){
        .eye = {0.0f, 0.0f, 3.0f},
        .target = {0.0f, 0.0f, 0.0f},
        .up = {0.0f, 1.0f, 0.0f},
        .fov_y_deg = 40.0f,
        .width = width,
        .height = height,
    };
}

fc_code fc_test_write_render_sequence(fc_buf *out, uint32_t request_id, uint32_t width, uint32_t height,
                                      const fc_render_request *request, fc_error *err)
{
    fc_frame frame;
    fc_camera camera;
    fc_code code = fc_test_cube_frame(&frame, err);
    if (code != FC_OK)
        return code;
    fc_test_front_camera(width, height, &camera);
    code = fc_wire_write_frame(out, request_id, &frame, err);
    if (code == FC_OK)
        code = fc_wire_write_camera(out, request_id + 1, &camera, err);
    if (code == FC_OK)
        code = fc_wire_write_render(out, request_id + 2, request, err);
    fc_frame_free(&frame);
    return code;
}

fc_code fc_test_render(int fd, uint32_t request_id, uint32_t width, uint32_t height,
                       const fc_render_request *request, fc_test_message *reply, fc_error *err)
{
    fc_buf out;
    fc_buf_init(&out);
    fc_code code = fc_test_write_render_sequence(&out, request_id, width, height, request, err);
    if (code == FC_OK)
        code = fc_test_send(fd, out.data, out.len, err);
    fc_buf_free(&out);
    if (code == FC_OK)
        code = fc_test_read_message(fd, FC_TEST_IO_TIMEOUT_MS, reply, err);
    return code;
}
