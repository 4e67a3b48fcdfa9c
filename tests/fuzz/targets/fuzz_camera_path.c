/* fuzz_camera_path.c — libFuzzer target for the camera keyframe file of
 * `fluidcast render --camera-path` (client/cli/camera_path.c): the input is
 * the whole file.
 *
 * Beyond memory safety it checks the parser's contract: a refusal is
 * FC_ERR_PARSE, FC_ERR_LIMIT or FC_ERR_NOMEM naming the file and leaves no
 * keyframe behind; an accepted file has keyframes in strictly increasing frame
 * order with finite values and a fov in (0, 180), and the camera evaluated
 * at, between and around them is finite. */
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

static void check_path(const fc_camera_path *p)
{
    FUZZ_REQUIRE(p->count >= 1 && p->count <= FC_CAMERA_PATH_MAX_KEYS, "%u keyframes", (unsigned)p->count);
    const fc_camera base = {.up = {0, 0, 1}, .fov_y_deg = 40, .width = 64, .height = 48};
    for (uint32_t i = 0; i < p->count; i++) {
        const fc_camera_key *key = &p->keys[i];
        FUZZ_REQUIRE(i == 0 || key->frame > key[-1].frame, "frames do not increase at keyframe %u", (unsigned)i);
        FUZZ_REQUIRE(!key->has_fov || (key->fov_deg > 0 && key->fov_deg < 180), "fov %g", key->fov_deg);
        fc_camera c;
        /* Values near DBL_MAX may overflow the float camera: only evaluate moderate ones. */
        bool moderate = true;
        for (int k = 0; k < 3; k++)
            moderate = moderate && fabs(key->eye[k]) < 1e30 && fabs(key->target[k]) < 1e30 && fabs(key->up[k]) < 1e30;
        if (!moderate || i > 64)
            continue;
        fc_camera_path_at(p, key->frame, &base, &c);
        FUZZ_REQUIRE(c.eye[0] == (float)key->eye[0] && c.target[2] == (float)key->target[2],
                     "the camera at keyframe %u is not the keyframe's", (unsigned)i);
        check_camera_finite(&c);
        if (key->frame > 0) {
            fc_camera_path_at(p, key->frame - 1, &base, &c);
            (void)c;
        }
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
