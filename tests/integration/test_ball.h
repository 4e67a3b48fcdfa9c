/* test_ball.h — the scene of the client integration tests: a ball of particles
 * on a cubic lattice, seen from -y, whose picture and depth are known
 * analytically; plus writers for the particle files the CLI reads. */
#ifndef FC_TEST_BALL_H
#define FC_TEST_BALL_H

#include <stdbool.h>

#include "fluidcast_types.h"

/* Lattice points (i, j, k) * spacing with i^2 + j^2 + k^2 <= 8^2: about 2100
 * particles filling a ball of radius 0.5. The front-most particle on the view
 * axis sits exactly at (0, -0.5, 0). */
#define BALL_STEPS 8
#define BALL_SPACING 0.0625f
#define BALL_RADIUS (BALL_STEPS * BALL_SPACING)
/* The sphere radius the tests render with. */
#define BALL_SPHERE_RADIUS 0.05f
/* The camera: eye on the -y axis looking at the ball's centre, +z up. */
#define BALL_EYE_DISTANCE 4.0f
#define BALL_FOV_DEG 40.0f
/* Linear depth of the fluid surface along the view axis: eye to the front of
 * the particle at (0, -0.5, 0). */
#define BALL_FRONT_DEPTH (BALL_EYE_DISTANCE - BALL_RADIUS - BALL_SPHERE_RADIUS)

fc_code test_ball_frame(fc_frame *frame, fc_error *err);

/* The 8 corners of the ball's bounding box: a frame with the same bounds (so the
 * same floor and sky) whose particles stay clear of the image centre and of the
 * ring the tests sample outside the ball. */
fc_code test_ball_box_corners(fc_frame *frame, fc_error *err);

void test_ball_camera(uint32_t width, uint32_t height, fc_camera *cam);

/* Raw little-endian float32 xyz (.f32) and ASCII PLY. */
bool test_write_f32(const fc_frame *frame, const char *path);
bool test_write_ply(const fc_frame *frame, const char *path);

#endif
