/* test_hardening_gpu_oom.c — a real out-of-memory on the render path,
 * against the real fluidcastd. llvmpipe keeps its render targets in process
 * memory, so an address-space limit (RLIMIT_AS, set before exec) makes a huge
 * image run out of "GPU" memory for real. The limit is the daemon's VmPeak
 * under the same workload without the huge image, measured in a first run,
 * plus HEADROOM_MIB: more than the small renders ever need, less than the
 * render targets of the huge image.
 *
 * The huge RENDER gets ERROR RENDER mentioning memory; the daemon's memory
 * (address space and resident) is back near where it was before the huge
 * request without any other render, since the pipeline was rebuilt to release
 * the targets the request did get; another client is served before and after;
 * the failing client's next renders (depth checked against the analytic cube,
 * colour against its background) are right.
 *
 * AddressSanitizer reserves terabytes of address space, so no such limit can
 * be set under it: the test then says so and returns the skip code. */
#include <stdio.h>
#include <unistd.h>

#include "hardening_harness.h"
#include "test_scene.h"
#include "test_util.h"

#if defined(__SANITIZE_ADDRESS__)
#define UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define UNDER_ASAN 1
#endif
#endif
#ifndef UNDER_ASAN
#define UNDER_ASAN 0
#endif

enum {
    SKIP_CODE = 77,          /* SKIP_RETURN_CODE in CMakeLists.txt */
    HUGE_SIDE = 8192,        /* one 32-bit target of it is 256 MiB; a colour render needs several */
    HEADROOM_MIB = 640,      /* the first two such targets fit, the whole render does not */
    SLACK_MIB = 64,          /* a rebuilt pipeline's shaders, allocator slack: far below one target */
    RECOVERY_TIMEOUT_MS = 10000
};

static const char *const daemon_args[] = {"--max-image", "16384x16384", NULL};
/* One malloc arena: otherwise each thread may reserve 64 MiB of address space
 * for its own, as it happens, and the headroom would vary from run to run. */
static const char *const environment[] = {"MALLOC_ARENA_MAX=1", NULL};

/* The small renders both runs make: the cube's depth, then its colour over
 * the magenta background (which also compiles the colour passes). */
static void small_renders(int fd, uint32_t first_id)
{
    hx_expect_renders(fd, first_id);
    hx_send_magenta_background(fd, first_id + 3);
    hx_send_render(fd, first_id + 4, FC_FORMAT_RAW, FC_AOV_COLOR);
    hx_expect_magenta_image(fd, first_id + 4, NULL);
}

/* The address space the daemon needs without the huge image, in KiB. */
static long long measure_peak_kib(void)
{
    fc_test_daemon_setup setup = {.extra_args = daemon_args, .environment = environment};
    hx_env env;
    if (!hx_env_start_with(&env, &setup))
        return -1;
    int fd = hx_connect_greeted(&env, 0);
    small_renders(fd, 10);
    small_renders(fd, 20);
    hx_expect_witness_served(&env);
    long long peak = hx_daemon_status_kib(&env, "VmPeak");
    close(fd);
    hx_env_stop(&env);
    CHECK_MSG(peak > 0, "cannot read the daemon's VmPeak");
    return peak;
}

/* FRAME, CAMERA at HUGE_SIDE and RENDER with ids first_id..first_id+2. */
static void send_huge_request(int fd, uint32_t first_id)
{
    fc_buf out;
    fc_error err;
    fc_buf_init(&out);
    fc_render_request request = {FC_FORMAT_RAW, 0, FC_AOV_COLOR};
    CHECK_CODE(fc_test_write_render_sequence(&out, first_id, HUGE_SIDE, HUGE_SIDE, &request, &err), FC_OK);
    hx_send_buf(fd, &out);
    fc_buf_free(&out);
}

/* Waits up to RECOVERY_TIMEOUT_MS for the daemon's `field` of /proc to be
 * below `limit_kib`; returns the last value read. */
static long long wait_below(const hx_env *env, const char *field, long long limit_kib)
{
    double deadline = hx_now_ms() + RECOVERY_TIMEOUT_MS;
    long long kib = hx_daemon_status_kib(env, field);
    while (kib >= limit_kib && hx_now_ms() < deadline) {
        hx_sleep_ms(20);
        kib = hx_daemon_status_kib(env, field);
    }
    return kib;
}

static void run_limited(long long peak_kib)
{
    fc_test_daemon_setup setup = {
        .extra_args = daemon_args,
        .environment = environment,
        .address_space_limit = (uint64_t)peak_kib * 1024 + (uint64_t)HEADROOM_MIB * 1024 * 1024,
    };
    hx_env env;
    if (!hx_env_start_with(&env, &setup))
        return;
    int fd = hx_connect_greeted(&env, 0);
    small_renders(fd, 10);
    hx_expect_witness_served(&env);
    long long size_before = hx_daemon_status_kib(&env, "VmSize");
    long long rss_before = hx_daemon_status_kib(&env, "VmRSS");

    send_huge_request(fd, 20);
    hx_expect_error_mentioning(fd, 22, FC_ERR_RENDER, "memory");
    /* Before any other render, which would shrink the targets it shares with
     * the huge one anyway: the rebuild alone must release them. */
    long long size_after = wait_below(&env, "VmSize", size_before + SLACK_MIB * 1024);
    long long rss_after = wait_below(&env, "VmRSS", rss_before + SLACK_MIB * 1024);
    printf("VmPeak of the plain run %lld KiB, limit %lld KiB; before the huge image VmSize %lld KiB, VmRSS %lld "
           "KiB; after it %lld and %lld KiB\n",
           peak_kib, (long long)(setup.address_space_limit / 1024), size_before, rss_before, size_after, rss_after);
    CHECK_MSG(size_before > 0 && size_after < size_before + SLACK_MIB * 1024,
              "VmSize %lld KiB after the failed image, %lld before", size_after, size_before);
    CHECK_MSG(rss_before > 0 && rss_after < rss_before + SLACK_MIB * 1024,
              "VmRSS %lld KiB after the failed image, %lld before", rss_after, rss_before);

    hx_expect_witness_served(&env);
    small_renders(fd, 30);
    close(fd);
    hx_env_stop(&env);
}

int main(void)
{
    if (UNDER_ASAN) {
        printf("skipped: AddressSanitizer reserves terabytes of address space, so RLIMIT_AS cannot be set\n");
        return SKIP_CODE;
    }
    long long peak_kib = measure_peak_kib();
    if (peak_kib > 0)
        run_limited(peak_kib);
    return hx_exit_status(0);
}
