/* hardening_harness.h — the hostile-input matrix against the real fluidcastd.
 *
 * A case is a few offending bytes sent on a fresh connection, the exact reply
 * PROTOCOL.md prescribes for them (an ERROR with its code and request id, or
 * nothing), and what becomes of the connection (open or closed). The runner
 * checks all of it, then checks that a witness, a well-behaved client connected
 * the whole time, still gets a correct image, and that the offending connection,
 * where it stays open, still renders correctly too.
 *
 * Offending bytes are written out field by field here (little endian, as
 * PROTOCOL.md lays them out), not with the codec under test; only the
 * well-behaved render sequences use the codec. */
#ifndef FC_HARDENING_HARNESS_H
#define FC_HARDENING_HARNESS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "daemon_process.h"
#include "wire.h"

/* Every offending message carries this request id, so the ERROR must echo it. */
#define HX_BAD_ID 666u
/* Ids of the well-behaved messages a case sends before its offending one. */
#define HX_PRELUDE_ID 600u
/* Size of every well-behaved render: tiny, so the matrix stays fast on llvmpipe. */
#define HX_IMAGE_SIDE 32u

/* ---- raw messages ---- */

/* Appends a 16-byte header with magic "FCST" and the given fields. */
void hx_header(fc_buf *out, uint16_t type, uint16_t flags, uint32_t request_id, uint32_t length);
/* Starts a message whose length is patched by hx_end; returns where it starts. */
size_t hx_begin(fc_buf *out, uint16_t type, uint32_t request_id);
void hx_end(fc_buf *out, size_t start);
void hx_u16(fc_buf *out, uint16_t v);
void hx_u32(fc_buf *out, uint32_t v);
void hx_u64(fc_buf *out, uint64_t v);
void hx_f32(fc_buf *out, float v);
void hx_str(fc_buf *out, const char *s);
void hx_bytes(fc_buf *out, const void *p, size_t n);
/* A HELLO for versions [vmin, vmax] asking for `capabilities`. */
void hx_hello(fc_buf *out, uint32_t request_id, uint32_t vmin, uint32_t vmax, uint32_t capabilities);

/* ---- one case ---- */

typedef enum hx_prologue {
    HX_RAW = 0,        /* nothing: the case's bytes are the first on the connection */
    HX_GREETED,        /* HELLO without capabilities, WELCOME read */
    HX_GREETED_ALL,    /* HELLO with every capability (FC_CAPS_ALL), WELCOME read */
    HX_PUBLISHING      /* HX_GREETED_ALL, then PUBLISH to a session named after the case */
} hx_prologue;

typedef enum hx_outcome {
    HX_STAYS_OPEN = 0, /* the connection goes on: a full render on it must still work */
    HX_CLOSES          /* the daemon closes the connection after its reply (if any) */
} hx_outcome;

typedef struct hx_case {
    const char *name;
    hx_prologue prologue;
    /* Appends the offending bytes (and any well-behaved messages before them);
     * NULL for cases run with hx_run_case_bytes. */
    void (*build)(fc_buf *out);
    /* The ERROR code expected for HX_BAD_ID (BAD_MAGIC: for request id 0), or
     * FC_OK when the bytes are accepted without a reply (a HELLO: with its WELCOME). */
    fc_code expected;
    hx_outcome outcome;
    /* The client shuts down its sending side after the bytes (a message cut short). */
    bool half_close;
} hx_case;

/* The daemon and the witness every case of a test program shares. */
typedef struct hx_env {
    fc_test_daemon daemon;
    int witness_fd;
    uint32_t witness_next_id;
    struct hx_tls *tls;   /* FC_HARDENING_TRANSPORT=tls: every connection through TLS (hardening_tls.h); else NULL */
} hx_env;

/* Starts fluidcastd with extra_args (plus --log-level warn, and a certificate
 * when the run asks for TLS) and connects the witness. */
bool hx_env_start(hx_env *env, const char *const *extra_args);
/* The same with the daemon's process set up as `setup` says. */
bool hx_env_start_with(hx_env *env, const fc_test_daemon_setup *setup);
/* Checks the witness once more, closes it and requires a clean daemon exit. */
void hx_env_stop(hx_env *env);

/* Runs one case and every check described above. */
void hx_run_case(hx_env *env, const hx_case *c);
/* The same with bytes built by the caller (for tables of parameters). */
void hx_run_case_bytes(hx_env *env, const hx_case *c, const fc_buf *bytes);
void hx_run_cases(hx_env *env, const hx_case *cases, size_t count);

/* test_util.h counts failed checks per source file: a test's main returns
 * hx_exit_status(test_result()) so the harness's own checks count too. */
int hx_exit_status(int main_status);

/* ---- building blocks for cases the table cannot express ---- */

/* Connects (fd < 0 after a failed CHECK). */
int hx_connect(const hx_env *env);
/* Connects and completes HELLO/WELCOME asking for `capabilities`. */
int hx_connect_greeted(const hx_env *env, uint32_t capabilities);
/* PUBLISH to `session`, answered by SESSION_STATE. */
void hx_publish(int fd, const char *session);
void hx_send(int fd, const void *data, size_t size);
void hx_send_buf(int fd, fc_buf *out);   /* sends and empties out */
/* The next message is an ERROR echoing request_id with exactly `code` and a reason. */
void hx_expect_error(int fd, uint32_t request_id, fc_code code);
/* ...whose reason contains `phrase` (NULL: any reason). */
void hx_expect_error_mentioning(int fd, uint32_t request_id, fc_code code, const char *phrase);
/* The daemon closes the connection without sending anything more. */
void hx_expect_closed(int fd);
/* Appends FRAME (the test cube), CAMERA (front, HX_IMAGE_SIDE square) and
 * RENDER (RAW depth) with ids first_id..first_id+2. */
void hx_write_render_sequence(fc_buf *out, uint32_t first_id);
/* The next message is the IMAGE for render_id, its depths those of the cube
 * seen from the front (analytic centre depth, nothing in the corners). */
void hx_expect_cube_image(int fd, uint32_t render_id);
/* The next message answers render_id: either an ERROR with `code` whose
 * reason contains `phrase` (true), or the cube's correct IMAGE (false). */
bool hx_expect_cube_image_or_error(int fd, uint32_t render_id, fc_code code, const char *phrase);
/* A complete render sequence on fd, answered by the correct image. */
void hx_expect_renders(int fd, uint32_t first_id);
/* The witness renders correctly (a client is served while others misbehave). */
void hx_expect_witness_served(hx_env *env);
/* ---- scene images ---- */

/* BACKGROUND with the 4x4 magenta PNG (tests/integration/scene_fixtures.h):
 * accepted without a reply. */
void hx_send_magenta_background(int fd, uint32_t request_id);
/* RENDER alone (the connection's frame and camera stay as they are). */
void hx_send_render(int fd, uint32_t request_id, fc_image_format format, fc_aov aov);
/* The next message is the IMAGE for render_id: the cube's render sequence
 * camera in RAW colour over the magenta background, which fills the corners
 * while the fluid covers the centre. Its pixels are appended to `pixels`
 * (may be NULL) for comparisons. */
void hx_expect_magenta_image(int fd, uint32_t render_id, fc_buf *pixels);

/* The next message is of `type` and answers request_id. */
void hx_expect_reply_type(int fd, uint32_t request_id, uint16_t type);

/* A field of /proc/PID/status of the daemon in KiB ("VmPeak", "VmRSS"), or -1 when unreadable. */
long long hx_daemon_status_kib(const hx_env *env, const char *field);
/* Descriptors the daemon holds open (from /proc), or -1 when unreadable. */
int hx_daemon_open_fds(const hx_env *env);
/* Waits up to timeout_ms for the daemon to hold at most `count` descriptors. */
bool hx_wait_daemon_fds_at_most(const hx_env *env, int count, int timeout_ms);
double hx_now_ms(void);
void hx_sleep_ms(int ms);

#endif
