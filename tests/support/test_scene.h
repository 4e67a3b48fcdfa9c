/* test_scene.h — a small fluid scene whose picture is known in outline: a cube
 * of particles at the origin seen from +z, so the image centre shows fluid and
 * the corners show background. Plus a client that sends it and asks for a render. */
#ifndef FC_TEST_SCENE_H
#define FC_TEST_SCENE_H

#include "test_socket.h"

/* Particles in the cube: side^3 particles `spacing` apart, centred at the origin. */
#define FC_TEST_CUBE_SIDE 6
#define FC_TEST_CUBE_SPACING 0.1f

/* Allocates the cube frame (free with fc_frame_free). */
fc_code fc_test_cube_frame(fc_frame *frame, fc_error *err);

/* Eye at (0,0,3) looking at the origin, +y up, 40 degrees vertical fov. */
void fc_test_front_camera(uint32_t width, uint32_t height, fc_camera *camera);

/* Appends FRAME (the cube, request_id), CAMERA (request_id+1) and RENDER
 * (request_id+2) to out. */
fc_code fc_test_write_render_sequence(fc_buf *out, uint32_t request_id, uint32_t width, uint32_t height,
                                      const fc_render_request *request, fc_error *err);

/* Sends the render sequence and reads the one reply (an IMAGE or an ERROR). */
fc_code fc_test_render(int fd, uint32_t request_id, uint32_t width, uint32_t height,
                       const fc_render_request *request, fc_test_message *reply, fc_error *err);

#endif
