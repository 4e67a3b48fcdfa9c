/* fuzz_camera_path.c — libFuzzer target for the camera keyframe file of
 * `fluidcast render --camera-path` (client/cli/camera_path.c): the input is
 * the whole file.
 *
 * Beyond memory safety it checks the parser's contract: a refusal is
 * FC_ERR_PARSE, FC_ERR_LIMIT or FC_ERR_NOMEM naming the file and leaves no
 * keyframe behind; an accepted file has keyframes in strictly increasing frame
 * order, and the camera on each is the keyframe's, with finite values, a fov
 * in (0, 180) and its eye apart from its target as the floats the daemon gets
 * (the file's doubles are checked after their conversion). */
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "camera_path.h"
#include "fuzz_check.h"

#define NAME "fuzz.json"

static void check_refusal(fc_code code, const fc_error *err, const fc_camera_path *p)
{
    fuzz_require_reported(code, err);
    FUZZ_REQUIRE(code == FC_ERR_PARSE || code == FC_ERR_LIMIT || code == FC_ERR_NOMEM, "unexpected code %d: %s",
                 (int)code, err->message);
    FUZZ_REQUIRE(strncmp(err->message, NAME ":", strlen(NAME ":")) == 0, "message does not name the file: %s",
                 err->message);
    FUZZ_REQUIRE(p->keys == NULL && p->count == 0, "a refused file left %u keyframes", (unsigned)p->count);
}

static void check_camera_finite(const fc_camera *c)
{
    for (int k = 0; k < 3; k++)
        FUZZ_REQUIRE(isfinite(c->eye[k]) && isfinite(c->target[k]) && isfinite(c->up[k]), "non-finite camera");
    FUZZ_REQUIRE(c->fov_y_deg > 0.0f && c->fov_y_deg < 180.0f, "fov %g", (double)c->fov_y_deg);
}

/* The camera on keyframe i is the keyframe's and passes what the daemon's
 * fc_camera_validate checks of it that the file decides: finite values, a fov
 * in (0, 180) and an eye apart from the target, as the floats sent. (The up of
 * a keyframe without one is the sequence's, unknown here.) */
static void check_key_camera(const fc_camera_path *p, uint32_t i, const fc_camera *base)
{
    const fc_camera_key *key = &p->keys[i];
    fc_camera c;
    fc_camera_path_at(p, key->frame, base, &c);
    FUZZ_REQUIRE(memcmp(c.eye, key->eye, sizeof c.eye) == 0 && memcmp(c.target, key->target, sizeof c.target) == 0 &&
                 (!key->has_fov || c.fov_y_deg == key->fov_deg),
                 "the camera at keyframe %u is not the keyframe's", (unsigned)i);
    check_camera_finite(&c);
    FUZZ_REQUIRE(c.eye[0] != c.target[0] || c.eye[1] != c.target[1] || c.eye[2] != c.target[2],
                 "the camera at keyframe %u has its eye on its target", (unsigned)i);
    if (key->frame > 0)
        fc_camera_path_at(p, key->frame - 1, base, &c);
}

static void check_path(const fc_camera_path *p)
{
    FUZZ_REQUIRE(p->count >= 1 && p->count <= FC_CAMERA_PATH_MAX_KEYS, "%u keyframes", (unsigned)p->count);
    const fc_camera base = {.up = {0, 0, 1}, .fov_y_deg = 40, .width = 64, .height = 48};
    for (uint32_t i = 0; i < p->count; i++) {
        const fc_camera_key *key = &p->keys[i];
        FUZZ_REQUIRE(i == 0 || key->frame > key[-1].frame, "frames do not increase at keyframe %u", (unsigned)i);
        FUZZ_REQUIRE(!key->has_fov || (key->fov_deg > 0.0f && key->fov_deg < 180.0f), "fov %g", (double)key->fov_deg);
        if (i <= 64)
            check_key_camera(p, i, &base);
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    fc_camera_path p;
    fc_error err = {FC_OK, ""};
    fc_code code = fc_camera_path_parse((const char *)data, size, NAME, &p, &err);
    if (code != FC_OK) {
        check_refusal(code, &err, &p);
        return 0;
    }
    check_path(&p);
    fc_camera_path_free(&p);
    return 0;
}
