/* test_service_uploads.c — packed uploads against the real fluidcastd: a zstd
 * frame renders exactly like the plain one in fewer bytes; a 16-bit quantised
 * frame whose positions lie on the quantisation grid renders exactly like the
 * plain one, and an arbitrary one stays within the documented error bound;
 * encodings the connection did not negotiate are refused with their codes. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "service_support.h"
#include "test_util.h"

enum { WIDTH = 81, HEIGHT = 61 };

static const char *const daemon_args[] = {"--max-image", "256x256", NULL};

/* Sends the frame as `options` say and renders it with the axis camera. */
static fc_code upload_and_render(fc_client *c, const fc_frame *frame, const fc_upload_options *options,
                                 fc_aov aov, fc_upload_stats *stats, fc_image_result *image, float eye_z)
{
    fc_camera cam;
    fc_settings settings;
    svc_axis_camera(eye_z, WIDTH, HEIGHT, &cam);
    svc_settings(&settings);
    fc_render_request request = {.format = FC_FORMAT_RAW, .quality = 0, .aov = aov};
    fc_error err;
    fc_code code = fc_client_upload_frame(c, frame, options, stats, &err);
    if (code == FC_OK)
        code = fc_client_set_camera(c, &cam, &err);
    if (code == FC_OK)
        code = fc_client_set_settings(c, &settings, &err);
    if (code == FC_OK)
        code = fc_client_render(c, &request, image, &err);
    if (code != FC_OK)
        fprintf(stderr, "upload and render: %s\n", err.message);
    return code;
}

static bool same_image(const fc_image_result *a, const fc_image_result *b)
{
    return a->data && b->data && a->size == b->size && memcmp(a->data, b->data, a->size) == 0;
}

/* The ball of the client tests, offset so no coordinate is on a quantisation grid. */
static fc_frame ball(void)
{
    const int steps = 6;
    const float spacing = 0.07f;
    fc_frame f;
    fc_error err;
    uint64_t n = 0;
    for (int pass = 0; pass < 2; pass++) {
        if (pass == 1)
            CHECK_CODE(fc_frame_alloc(&f, n, FC_ATTR_VELOCITY, &err), FC_OK);
        n = 0;
        for (int i = -steps; i <= steps; i++)
            for (int j = -steps; j <= steps; j++)
                for (int k = -steps; k <= steps; k++) {
                    if (i * i + j * j + k * k > steps * steps)
                        continue;
                    if (pass == 1) {
                        float *p = f.positions + 3 * n;
                        p[0] = 0.0123f + i * spacing;
                        p[1] = -0.0071f + j * spacing;
                        p[2] = 0.0037f + k * spacing;
                        f.velocity[3 * n] = f.velocity[3 * n + 1] = f.velocity[3 * n + 2] = 0.25f;
                    }
                    n++;
                }
    }
    return f;
}

static void test_zstd_is_identical_and_smaller(fc_client *c)
{
    fc_frame f = ball();
    fc_upload_options zstd = {.encoding = FC_UPLOAD_ZSTD};
    fc_upload_stats plain_stats, zstd_stats;
    fc_image_result plain = {0}, packed = {0};
    CHECK_CODE(upload_and_render(c, &f, NULL, FC_AOV_COLOR, &plain_stats, &plain, 3.0f), FC_OK);
    CHECK_CODE(upload_and_render(c, &f, &zstd, FC_AOV_COLOR, &zstd_stats, &packed, 3.0f), FC_OK);
    CHECK_MSG(same_image(&plain, &packed), "the zstd upload renders differently");
    CHECK(plain_stats.raw_bytes == plain_stats.wire_bytes);
    CHECK(plain_stats.raw_bytes == 16 + 16 + f.count * 24);
    CHECK(zstd_stats.raw_bytes == plain_stats.raw_bytes);
    CHECK_MSG(zstd_stats.wire_bytes < zstd_stats.raw_bytes, "zstd sent %llu bytes for %llu",
              (unsigned long long)zstd_stats.wire_bytes, (unsigned long long)zstd_stats.raw_bytes);
    fc_image_result_free(&plain);
    fc_image_result_free(&packed);
    fc_frame_free(&f);
}

/* Positions on multiples of (hi - lo) / 65535 = 1/1024 decode exactly: the
 * quantised upload must render the very same image. The outliers at the box
 * corners fix lo and hi and lie outside the view. */
static void test_quantised_grid_frame_is_identical(fc_client *c)
{
    fc_frame grid = {0};
    fc_error err;
    CHECK_CODE(svc_grid_frame(0.0f, &grid, &err), FC_OK);
    fc_frame f;
    CHECK_CODE(fc_frame_alloc(&f, grid.count + 2, 0, &err), FC_OK);
    const float step = 1.0f / 1024.0f;
    for (uint64_t i = 0; i < 3 * grid.count; i++)
        f.positions[i] = roundf(grid.positions[i] / step) * step;
    for (int k = 0; k < 3; k++) {
        f.positions[3 * grid.count + k] = -32768 * step;
        f.positions[3 * grid.count + 3 + k] = 32767 * step;
    }
    fc_upload_options quantise = {.encoding = FC_UPLOAD_QUANTIZE16};
    fc_upload_stats stats;
    fc_image_result plain = {0}, packed = {0};
    CHECK_CODE(upload_and_render(c, &f, NULL, FC_AOV_COLOR, NULL, &plain, 3.0f), FC_OK);
    CHECK_CODE(upload_and_render(c, &f, &quantise, FC_AOV_COLOR, &stats, &packed, 3.0f), FC_OK);
    CHECK_MSG(same_image(&plain, &packed), "the quantised grid frame renders differently");
    /* 6 bytes a position instead of 12, plus the packed header and the box. */
    CHECK(stats.wire_bytes == 16 + 16 + 40 + 6 * f.count + (f.count % 2) * 2);
    fc_image_result_free(&plain);
    fc_image_result_free(&packed);
    fc_frame_free(&f);
    fc_frame_free(&grid);
}

/* Depth seen along each pixel moves by no more than the positions do: within
 * the bound at every pixel where both images have fluid, away from the
 * silhouettes where a pixel can switch spheres. */
static void test_quantised_ball_within_bound(fc_client *c)
{
    fc_frame f = ball();
    float lo[3], hi[3];
    fc_frame_bounds(&f, lo, hi);
    double bound = 0.0;
    for (int k = 0; k < 3; k++)
        bound = fmax(bound, fc_quantize_error_bound(lo[k], hi[k]));
    fc_upload_options both = {.encoding = FC_UPLOAD_QUANTIZE16 | FC_UPLOAD_ZSTD};
    fc_upload_stats stats;
    fc_image_result plain = {0}, packed = {0};
    CHECK_CODE(upload_and_render(c, &f, NULL, FC_AOV_DEPTH, NULL, &plain, 3.0f), FC_OK);
    CHECK_CODE(upload_and_render(c, &f, &both, FC_AOV_DEPTH, &stats, &packed, 3.0f), FC_OK);
    CHECK(stats.wire_bytes < stats.raw_bytes / 2);
    if (plain.size == packed.size && plain.size == (size_t)WIDTH * HEIGHT * 4) {
        size_t covered = 0, within = 0;
        double worst = 0.0;
        for (size_t i = 0; i < (size_t)WIDTH * HEIGHT; i++) {
            float a, b;
            memcpy(&a, plain.data + 4 * i, 4);
            memcpy(&b, packed.data + 4 * i, 4);
            if (a == 0.0f || b == 0.0f)
                continue;
            covered++;
            double d = fabs((double)a - b);
            /* sqrt(3) x the per-axis bound moves a sphere; 1e-5 covers the depth's float rounding. */
            within += d <= sqrt(3.0) * bound + 1e-5;
            worst = fmax(worst, d);
        }
        CHECK_MSG(covered > 300, "only %zu pixels show fluid", covered);
        CHECK_MSG(within >= covered * 97 / 100, "%zu of %zu pixels within %.2g (worst %.2g)", within, covered,
                  sqrt(3.0) * bound, worst);
        CHECK_NEAR(svc_raw_centre(&packed), svc_raw_centre(&plain), sqrt(3.0) * bound + 1e-5);
    } else {
        CHECK_MSG(0, "depth images of %zu and %zu bytes", plain.size, packed.size);
    }
    fc_image_result_free(&plain);
    fc_image_result_free(&packed);
    fc_frame_free(&f);
}

/* Sends the grid as FRAME_PACKED; extra_bits are set in the encoding field after
 * encoding (a writer refuses unknown bits, a reader must too). */
static bool send_packed(int fd, uint32_t id, uint32_t encoding, uint8_t extra_bits)
{
    fc_frame f = {0};
    fc_error err;
    fc_buf b;
    fc_buf_init(&b);
    bool ok = svc_grid_frame(0.0f, &f, &err) == FC_OK &&
              fc_wire_write_frame_packed(&b, id, &f, encoding, 0, &err) == FC_OK;
    if (ok)
        b.data[FC_WIRE_HEADER_SIZE] |= extra_bits;
    ok = ok && svc_send(fd, &b);
    fc_buf_free(&b);
    fc_frame_free(&f);
    return ok;
}

static void test_encodings_need_negotiation(const fc_test_daemon *d)
{
    fc_welcome welcome;
    fc_error remote;
    int none = svc_raw_connect(d->port, 0, 0, &welcome);
    CHECK(welcome.capabilities == 0);
    CHECK(send_packed(none, 5, FC_PACK_ZSTD, 0) && svc_expect_error(none, 5, FC_ERR_UNKNOWN_TYPE, &remote));
    close(none);
    int quantise_only = svc_raw_connect(d->port, FC_CAP_QUANTIZE16 | 0x100, 0, &welcome);
    CHECK_MSG(welcome.capabilities == FC_CAP_QUANTIZE16, "granted 0x%x", welcome.capabilities);
    CHECK(send_packed(quantise_only, 6, FC_PACK_ZSTD, 0) &&
          svc_expect_error(quantise_only, 6, FC_ERR_BAD_STATE, &remote));
    /* The granted encoding is accepted: the next message's error is the next one answered. */
    CHECK(send_packed(quantise_only, 7, FC_PACK_QUANTIZE16, 0) &&
          send_packed(quantise_only, 8, FC_PACK_QUANTIZE16, 0x10) &&
          svc_expect_error(quantise_only, 8, FC_ERR_MALFORMED, &remote));
    close(quantise_only);
}

/* An encoding the library does not know is refused unsent; the connection stays usable. */
static void test_unknown_encoding_is_refused_unsent(fc_client *c)
{
    fc_frame f = {0};
    fc_error err;
    CHECK_CODE(svc_grid_frame(0.0f, &f, &err), FC_OK);
    fc_upload_options bogus = {.encoding = 0x80};
    CHECK_CODE(fc_client_upload_frame(c, &f, &bogus, NULL, &err), FC_ERR_USAGE);
    fc_image_result image = {0};
    CHECK_CODE(upload_and_render(c, &f, NULL, FC_AOV_DEPTH, NULL, &image, 3.0f), FC_OK);
    CHECK_NEAR(svc_raw_centre(&image), svc_axis_depth(3.0f, 0.0f), 0.01);
    fc_image_result_free(&image);
    fc_frame_free(&f);
}

int main(void)
{
    fc_test_daemon daemon;
    svc_start_daemon(&daemon, daemon_args);
    fc_client *c = svc_client(&daemon, "uploads");
    CHECK(c != NULL);
    if (c) {
        fc_server_info info;
        fc_client_server_info(c, &info);
        CHECK(info.capabilities ==
              (FC_SERVER_CAN_STREAM | FC_SERVER_CAN_ZSTD | FC_SERVER_CAN_QUANTIZE16 | FC_SERVER_CAN_DEVICE));
        test_zstd_is_identical_and_smaller(c);
        test_quantised_grid_frame_is_identical(c);
        test_quantised_ball_within_bound(c);
        test_unknown_encoding_is_refused_unsent(c);
        fc_client_close(c);
    }
    test_encodings_need_negotiation(&daemon);
    CHECK(svc_stop_daemon(&daemon));
    return test_result();
}
