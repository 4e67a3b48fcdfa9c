/* test_srv_dns.c — "srv:" addresses against a real DNS server (dnsmasq on a
 * loopback port) and three real fluidcastd daemons: a producer and two viewers
 * of each of 20 sessions, all given only the SRV name, meet on one daemon
 * (each daemon's own session list says so, and the viewers receive the
 * producer's frame), the sessions spread over all three; when a daemon goes
 * away its sessions fall back alike for every client and the others' stay;
 * session-less connections pick by weight; the CLI's stream and watch meet too;
 * and the failures (no such name, the "." target, a bad FLUIDCAST_DNS_SERVER)
 * have their codes. Skipped (77) when dnsmasq is not installed. */
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "cli_runner.h"
#include "dns_server.h"
#include "fc_error.h"
#include "fc_frame.h"
#include "service_support.h"
#include "test_ball.h"
#include "test_util.h"

enum { DAEMONS = 3, SESSIONS = 20, VIEWERS = 2, SIZE = 32, SKIP = 77 };

#define SRV_NAME "_fluidcast._tcp.fc.test"
#define SRV_ADDRESS "srv:" SRV_NAME

static const char *const daemon_args[] = {"--max-image", "256x256", NULL};

typedef struct meeting {
    char name[32];
    fc_client *producer;
    fc_client *viewers[VIEWERS];
} meeting;

static int daemon_of(const fc_test_daemon *daemons, const char *address)
{
    const char *colon = address ? strrchr(address, ':') : NULL;
    for (int k = 0; colon && k < DAEMONS; k++)
        if ((unsigned)atoi(colon + 1) == daemons[k].port)
            return k;
    return -1;
}

static fc_client *connect_for(const char *session, fc_error *err)
{
    fc_connect_options options = {.client_name = "srv test", .reply_timeout_ms = 60000};
    fc_client *c = NULL;
    if (fc_client_connect_session(SRV_ADDRESS, session, &options, &c, err) != FC_OK)
        return NULL;
    return c;
}

/* Producer first, then the viewers; every one given the SRV name only. */
static void open_meeting(meeting *m, int index)
{
    fc_error err;
    snprintf(m->name, sizeof m->name, "sim-%02d", index);
    m->producer = connect_for(m->name, &err);
    CHECK_MSG(m->producer, "%s: producer: %s", m->name, err.message);
    if (m->producer)
        CHECK_MSG(fc_client_publish(m->producer, m->name, NULL, &err) == FC_OK, "%s: %s", m->name, err.message);
    fc_render_request png = {.format = FC_FORMAT_PNG, .quality = 90, .aov = FC_AOV_COLOR};
    for (int v = 0; v < VIEWERS; v++) {
        m->viewers[v] = connect_for(m->name, &err);
        CHECK_MSG(m->viewers[v], "%s: viewer %d: %s", m->name, v, err.message);
        if (m->viewers[v])
            CHECK_MSG(fc_client_subscribe(m->viewers[v], m->name, &png, SIZE, SIZE, NULL, &err) == FC_OK,
                      "%s: subscribe: %s", m->name, err.message);
    }
}

/* The producer's frame reaches both viewers: they are on its daemon. */
static void check_frame_arrives(meeting *m)
{
    fc_frame frame = {0};
    fc_error err;
    if (!m->producer || svc_grid_frame(0.0f, &frame, &err) != FC_OK)
        return;
    CHECK_MSG(fc_client_upload_frame(m->producer, &frame, NULL, NULL, &err) == FC_OK, "%s: %s", m->name,
              err.message);
    fc_frame_free(&frame);
    for (int v = 0; v < VIEWERS; v++) {
        fc_stream_image img;
        if (!m->viewers[v])
            continue;
        fc_code code = fc_client_next_image(m->viewers[v], &img, &err);
        CHECK_MSG(code == FC_OK && !img.ended && img.image.width == SIZE && img.frame_number == 1,
                  "%s viewer %d: code %d (%s), ended %d, %ux%u", m->name, v, code, code ? err.message : "",
                  code ? 0 : img.ended, code ? 0 : img.image.width, code ? 0 : img.image.height);
        if (code == FC_OK)
            fc_stream_image_free(&img);
    }
}

static void close_meeting(meeting *m)
{
    fc_client_close(m->producer);
    for (int v = 0; v < VIEWERS; v++)
        fc_client_close(m->viewers[v]);
    memset(m, 0, sizeof *m);
}

/* Asks every daemon directly for its sessions: each meeting is on exactly one,
 * with 1 producer and 2 viewers, the one every client reported connecting to;
 * returns where each session is in home[]. */
static void check_placement(const fc_test_daemon *daemons, const meeting *meetings, int home[SESSIONS])
{
    int per_daemon[DAEMONS] = {0};
    for (int s = 0; s < SESSIONS; s++)
        home[s] = -1;
    for (int k = 0; k < DAEMONS; k++) {
        fc_client *c = svc_client(&daemons[k], "lister");
        fc_session_status *list = NULL;
        uint32_t count = 0;
        fc_error err;
        CHECK_MSG(c && fc_client_list_sessions(c, &list, &count, &err) == FC_OK, "daemon %d: list", k);
        for (uint32_t i = 0; i < count; i++) {
            int s = atoi(list[i].name + 4);
            CHECK_MSG(home[s] == -1, "%s is on daemons %d and %d", list[i].name, home[s], k);
            CHECK_MSG(list[i].producers == 1 && list[i].viewers == VIEWERS, "%s on daemon %d: %u producer(s), %u viewer(s)",
                      list[i].name, k, list[i].producers, list[i].viewers);
            home[s] = k;
            per_daemon[k]++;
        }
        fc_session_list_free(list);
        fc_client_close(c);
    }
    for (int s = 0; s < SESSIONS; s++) {
        const meeting *m = &meetings[s];
        CHECK_MSG(home[s] >= 0, "%s is on no daemon", m->name);
        if (m->producer)
            CHECK_MSG(daemon_of(daemons, fc_client_address(m->producer)) == home[s], "%s: producer at %s", m->name,
                      fc_client_address(m->producer));
        for (int v = 0; v < VIEWERS; v++)
            if (m->viewers[v])
                CHECK_MSG(daemon_of(daemons, fc_client_address(m->viewers[v])) == home[s], "%s: viewer at %s",
                          m->name, fc_client_address(m->viewers[v]));
    }
    printf("sessions per daemon: %d %d %d\n", per_daemon[0], per_daemon[1], per_daemon[2]);
    for (int k = 0; k < DAEMONS; k++)
        CHECK_MSG(per_daemon[k] >= 1, "daemon %d got none of the %d sessions", k, SESSIONS);
}

/* Daemon `gone` stopped: its sessions move, the same way for every client of
 * each; the others' sessions stay where they were. */
static void check_fallback(const fc_test_daemon *daemons, const int home[SESSIONS], int gone)
{
    int moved = 0;
    for (int s = 0; s < SESSIONS; s++) {
        char name[32];
        snprintf(name, sizeof name, "sim-%02d", s);
        fc_error err;
        fc_client *a = connect_for(name, &err), *b = connect_for(name, &err);
        CHECK_MSG(a && b, "%s after daemon %d stopped: %s", name, gone, err.message);
        if (!a || !b) {
            fc_client_close(a);
            fc_client_close(b);
            continue;
        }
        int where = daemon_of(daemons, fc_client_address(a));
        CHECK_MSG(where == daemon_of(daemons, fc_client_address(b)), "%s: clients split over %s and %s", name,
                  fc_client_address(a), fc_client_address(b));
        CHECK_MSG(where != gone, "%s on the stopped daemon", name);
        CHECK_MSG(home[s] == gone || where == home[s], "%s moved from daemon %d to %d though %d stayed", name,
                  home[s], where, home[s]);
        moved += home[s] == gone;
        fc_client_close(a);
        fc_client_close(b);
    }
    CHECK_MSG(moved >= 1, "daemon %d held no session to move", gone);
}

/* Without a session the choice is by weight (the test's records: 10, 10, 10). */
static void check_sessionless(const fc_test_daemon *daemons)
{
    int hits[DAEMONS] = {0};
    for (int i = 0; i < 24; i++) {
        fc_client *c = NULL;
        fc_error err;
        CHECK_MSG(fc_client_connect(SRV_ADDRESS, NULL, &c, &err) == FC_OK, "%s", err.message);
        int where = c ? daemon_of(daemons, fc_client_address(c)) : -1;
        if (where >= 0)
            hits[where]++;
        fc_client_close(c);
    }
    CHECK_MSG(hits[0] + hits[1] + hits[2] == 24 && (hits[0] > 0) + (hits[1] > 0) + (hits[2] > 0) >= 2,
              "session-less connections went to %d %d %d", hits[0], hits[1], hits[2]);
}

static void check_failures(const char *dns_address)
{
    fc_client *c = NULL;
    fc_error err;
    CHECK_CODE(fc_client_connect_session("srv:_fluidcast._tcp.missing.test", "x", NULL, &c, &err), FC_ERR_CONNECT);
    CHECK_MSG(strstr(err.message, "missing.test") != NULL, "%s", err.message);
    CHECK_CODE(fc_client_connect_session("srv:_fluidcast._tcp.none.test", "x", NULL, &c, &err), FC_ERR_CONNECT);
    CHECK_MSG(strstr(err.message, "not offered") != NULL, "\".\" target: %s", err.message);
    CHECK_CODE(fc_client_connect_session("srv:_fluidcast._tcp.dead.test", "x", NULL, &c, &err), FC_ERR_CONNECT);
    CHECK_MSG(strstr(err.message, "none of its 1 target") != NULL, "dead target: %s", err.message);
    CHECK_CODE(fc_client_connect_session("srv:", "x", NULL, &c, &err), FC_ERR_USAGE);
    setenv("FLUIDCAST_DNS_SERVER", "not-an-address", 1);
    CHECK_CODE(fc_client_connect_session(SRV_ADDRESS, "x", NULL, &c, &err), FC_ERR_USAGE);
    CHECK_MSG(strstr(err.message, "FLUIDCAST_DNS_SERVER") != NULL, "%s", err.message);
    setenv("FLUIDCAST_DNS_SERVER", dns_address, 1);
    CHECK(c == NULL);
}

typedef struct cli_job {
    char dir[96];
    const char *args[16];
    cli_result result;
} cli_job;

static void *run_job(void *arg)
{
    cli_job *job = arg;
    cli_run(FLUIDCAST_CLI_PATH, job->dir, job->args, &job->result);
    return NULL;
}

static int session_home(const fc_test_daemon *daemons, const char *session, uint32_t viewers)
{
    for (int tries = 0; tries < 500; tries++) {
        for (int k = 0; k < DAEMONS; k++) {
            fc_client *c = svc_client(&daemons[k], "waiter");
            fc_session_status *list = NULL;
            uint32_t count = 0;
            fc_error err;
            int found = -1;
            if (c && fc_client_list_sessions(c, &list, &count, &err) == FC_OK)
                for (uint32_t i = 0; i < count; i++)
                    if (strcmp(list[i].name, session) == 0 && list[i].viewers == viewers)
                        found = k;
            fc_session_list_free(list);
            fc_client_close(c);
            if (found >= 0)
                return found;
        }
        svc_sleep_ms(20);
    }
    return -1;
}

/* fluidcast watch and stream with --server srv:...: they say where they went, and meet. */
static void check_cli(const fc_test_daemon *daemons, const char *base)
{
    char frame_path[128];
    snprintf(frame_path, sizeof frame_path, "%s/frame.f32", base);
    fc_frame frame = {0};
    fc_error err;
    CHECK(svc_grid_frame(0.0f, &frame, &err) == FC_OK && test_write_f32(&frame, frame_path));
    fc_frame_free(&frame);

    cli_job watch = {.args = {"watch", "--server", SRV_ADDRESS, "--session", "cli-dam", "--size",
                              "32x32", NULL}};
    snprintf(watch.dir, sizeof watch.dir, "%s/watch", base);
    mkdir(watch.dir, 0700);
    pthread_t thread;
    pthread_create(&thread, NULL, run_job, &watch);
    int home = session_home(daemons, "cli-dam", 1);
    CHECK_MSG(home >= 0, "the watcher never subscribed");

    cli_result stream;
    const char *stream_args[] = {"stream", frame_path, "--server", SRV_ADDRESS, "--session", "cli-dam", "--size", "32x32", "--radius",
                                 "0.05", NULL};
    cli_run(FLUIDCAST_CLI_PATH, base, stream_args, &stream);
    pthread_join(thread, NULL);
    char expected[96];
    snprintf(expected, sizeof expected, SRV_ADDRESS " -> localhost:%u (session cli-dam)",
             home >= 0 ? (unsigned)daemons[home].port : 0u);
    CHECK_MSG(stream.status == 0 && strstr(stream.err, expected), "stream %d, expected \"%s\":\n%s%s", stream.status,
              expected, stream.out, stream.err);
    CHECK_MSG(watch.result.status == 0 && strstr(watch.result.err, expected) && strstr(watch.result.out, "1 image(s), session ended"),
              "watch %d, expected \"%s\":\n%s%s", watch.result.status, expected, watch.result.out, watch.result.err);
}

int main(void)
{
    if (!fc_test_dns_binary()) {
        printf("SKIP: dnsmasq is not installed (deploy/setup.sh installs dnsmasq-base)\n");
        return SKIP;
    }
    char base[] = "/tmp/fc-srv-XXXXXX";
    if (!mkdtemp(base))
        return 1;
    fc_test_daemon daemons[DAEMONS];
    for (int k = 0; k < DAEMONS; k++)
        svc_start_daemon(&daemons[k], daemon_args);

    char records[DAEMONS + 3][128];
    const char *lines[DAEMONS + 4];
    for (int k = 0; k < DAEMONS; k++) {
        snprintf(records[k], sizeof records[k], "srv-host=" SRV_NAME ",localhost,%u,0,10", (unsigned)daemons[k].port);
        lines[k] = records[k];
    }
    /* "." target (dnsmasq: no target given) and a target where nothing listens */
    snprintf(records[DAEMONS], sizeof records[0], "srv-host=_fluidcast._tcp.none.test");
    snprintf(records[DAEMONS + 1], sizeof records[0], "srv-host=_fluidcast._tcp.dead.test,localhost,1,0,10");
    lines[DAEMONS] = records[DAEMONS];
    lines[DAEMONS + 1] = records[DAEMONS + 1];
    lines[DAEMONS + 2] = NULL;
    fc_test_dns dns;
    if (!fc_test_dns_start(&dns, lines, SRV_NAME)) {
        for (int k = 0; k < DAEMONS; k++)
            svc_stop_daemon(&daemons[k]);
        fprintf(stderr, "dnsmasq did not start\n");
        return 1;
    }
    char dns_address[32];
    fc_test_dns_address(&dns, dns_address, sizeof dns_address);
    setenv("FLUIDCAST_DNS_SERVER", dns_address, 1);

    static meeting meetings[SESSIONS];
    for (int s = 0; s < SESSIONS; s++)
        open_meeting(&meetings[s], s);
    for (int s = 0; s < SESSIONS; s++)
        check_frame_arrives(&meetings[s]);
    int home[SESSIONS];
    check_placement(daemons, meetings, home);
    for (int s = 0; s < SESSIONS; s++)
        close_meeting(&meetings[s]);

    check_sessionless(daemons);
    check_failures(dns_address);
    check_cli(daemons, base);

    CHECK(svc_stop_daemon(&daemons[2]));
    check_fallback(daemons, home, 2);

    for (int k = 0; k < DAEMONS - 1; k++)
        CHECK(svc_stop_daemon(&daemons[k]));
    CHECK_MSG(fc_test_dns_stop(&dns), "dnsmasq did not exit cleanly (log in %s)", dns.dir);
    if (test_result() == 0) {
        char command[160];
        snprintf(command, sizeof command, "rm -rf %s %s", base, dns.dir);
        CHECK(system(command) == 0);
    }
    return test_result();
}
