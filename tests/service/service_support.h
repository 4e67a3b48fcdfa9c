/* service_support.h — what the session and streaming tests share: a daemon
 * started per test, raw-socket handshakes that ask for capabilities, small
 * scenes whose depth at the image centre is known analytically, and reading
 * RAW depth images. */
#ifndef FC_SERVICE_SUPPORT_H
#define FC_SERVICE_SUPPORT_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "fluidcast.h"
#include "support/daemon_process.h"
#include "support/test_socket.h"
#include "wire_session.h"

/* The grid scene: SVC_GRID_SIDE^3 particles SVC_GRID_SPACING apart, centred at
 * (0, 0, dz); one particle lies on the z axis at the front, z = SVC_GRID_FRONT + dz. */
#define SVC_GRID_SIDE 5
#define SVC_GRID_SPACING 0.1f
#define SVC_GRID_FRONT 0.2f
#define SVC_RADIUS 0.05f

/* Starts fluidcastd (software GL) with extra arguments; exits the test on failure. */
void svc_start_daemon(fc_test_daemon *d, const char *const *extra_args);
/* Stops it: true when it exited 0. */
bool svc_stop_daemon(fc_test_daemon *d);

/* "127.0.0.1:PORT" of the daemon. */
const char *svc_address(const fc_test_daemon *d);

/* The helpers print why they fail; the tests CHECK what they return (test_util.h
 * counts failures per file). */

/* Connects a raw socket to 127.0.0.1:port and exchanges HELLO (versions 1..1,
 * `capabilities`) / WELCOME. receive_buffer > 0 shrinks the socket's receive
 * buffer first (a viewer meant to stall). -1 on failure. */
int svc_raw_connect(uint16_t port, uint32_t capabilities, int receive_buffer, fc_welcome *welcome);
/* Sends the bytes in b and empties it. */
bool svc_send(int fd, fc_buf *b);
/* Reads one message: true when it is an ERROR answering request_id with `code`. */
bool svc_expect_error(int fd, uint32_t request_id, fc_code code, fc_error *remote);

/* Allocates the grid scene shifted by dz along z. */
fc_code svc_grid_frame(float dz, fc_frame *frame, fc_error *err);
/* Eye on the +z axis at distance eye_z from the origin, looking at it, +y up, 40 degrees. */
void svc_axis_camera(float eye_z, uint32_t width, uint32_t height, fc_camera *cam);
/* Linear depth of the front particle's sphere on the axis for that camera and dz. */
double svc_axis_depth(float eye_z, float dz);
/* Settings with the test radius and no smoothing. */
void svc_settings(fc_settings *s);

/* A connected client (libfluidcast), or NULL. */
fc_client *svc_client(const fc_test_daemon *d, const char *name);

/* The centre pixel of a RAW float image (depth AOV), width and height odd. */
float svc_raw_centre(const fc_image_result *image);

double svc_now_ms(void);
void svc_sleep_ms(int ms);

#endif
