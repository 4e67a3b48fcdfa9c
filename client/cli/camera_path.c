/* camera_path.c — see camera_path.h: the keyframe file, parsed with cJSON
 * and checked member by member, so that every message names the keyframe and
 * the member at fault. */
#include "camera_path.h"

#include <cjson/cJSON.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fc_error.h"
#include "fc_file.h"

/* ---- syntax ---- */

/* 1-based line and column of byte `at` of text. */
static void line_and_column(const char *text, size_t at, unsigned *line, unsigned *column)
{
    *line = 1;
    *column = 1;
    for (size_t i = 0; i < at; i++) {
        if (text[i] == '\n') {
            ++*line;
            *column = 1;
        } else
            ++*column;
    }
}

static fc_code syntax_error(const char *text, size_t size, const char *stop, const char *name, fc_error *err)
{
    size_t at = stop && stop >= text && stop <= text + size ? (size_t)(stop - text) : 0;
    unsigned line, column;
    line_and_column(text, at, &line, &column);
    if (at >= size)
        return fc_error_set(err, FC_ERR_PARSE, "%s:%u:%u: not valid JSON: the text ends too early", name, line,
                            column);
    return fc_error_set(err, FC_ERR_PARSE, "%s:%u:%u: not valid JSON (at '%c')", name, line, column,
                        text[at] >= 0x20 && text[at] < 0x7f ? text[at] : '?');
}

/* ---- one keyframe ---- */

typedef struct key_context {
    const char *name;     /* the file's */
    uint32_t index;       /* 1-based, for messages */
} key_context;

static fc_code key_error(const key_context *k, fc_error *err, const char *member, const char *what)
{
    return fc_error_set(err, FC_ERR_PARSE, "%s: keyframe %u: \"%s\" %s", k->name, (unsigned)k->index, member, what);
}

/* A JSON number as the float the camera carries, checked after the conversion:
 * false when it is not a number or is not finite as a float (1e39 is a finite
 * double but an infinite float). */
static bool number_as_float(const cJSON *item, float *out)
{
    if (!cJSON_IsNumber(item))
        return false;
    *out = (float)item->valuedouble;
    return isfinite(*out);
}

static fc_code read_vector(const key_context *k, const cJSON *item, float out[3], fc_error *err)
{
    bool ok = cJSON_IsArray(item) && cJSON_GetArraySize(item) == 3;
    int i = 0;
    for (const cJSON *e = ok ? item->child : NULL; e && ok; e = e->next, i++)
        ok = number_as_float(e, &out[i < 3 ? i : 2]);
    return ok ? FC_OK : key_error(k, err, item->string, "must be an array of 3 finite numbers");
}

static fc_code read_frame(const key_context *k, const cJSON *item, uint32_t *out, fc_error *err)
{
    double v = item->valuedouble;
    if (!cJSON_IsNumber(item) || !(v >= 0.0 && v <= 4294967295.0) || v != floor(v))
        return key_error(k, err, "frame", "must be a whole number 0..4294967295");
    *out = (uint32_t)v;
    return FC_OK;
}

/* Checked as a float: 179.99999999995 is below 180 as a double but rounds to
 * 180.0f, which fc_camera_validate (and so the daemon) refuses; 1e-50 rounds to 0. */
static fc_code read_fov(const key_context *k, const cJSON *item, float *out, fc_error *err)
{
    float v;
    if (!number_as_float(item, &v) || !(v > 0.0f && v < 180.0f))
        return key_error(k, err, "fov", "must be a number of degrees in (0, 180)");
    *out = v;
    return FC_OK;
}

enum { M_FRAME, M_EYE, M_TARGET, M_UP, M_FOV, MEMBER_COUNT };
static const char *const MEMBER_NAMES[MEMBER_COUNT] = {"frame", "eye", "target", "up", "fov"};

static int member_of(const char *name)
{
    for (int m = 0; m < MEMBER_COUNT; m++)
        if (name && strcmp(name, MEMBER_NAMES[m]) == 0)
            return m;
    return -1;
}

static fc_code read_member(const key_context *k, int m, const cJSON *item, fc_camera_key *key, fc_error *err)
{
    switch (m) {
    case M_FRAME:
        return read_frame(k, item, &key->frame, err);
    case M_EYE:
        return read_vector(k, item, key->eye, err);
    case M_TARGET:
        return read_vector(k, item, key->target, err);
    case M_UP:
        key->has_up = true;
        return read_vector(k, item, key->up, err);
    default:
        key->has_fov = true;
        return read_fov(k, item, &key->fov_deg, err);
    }
}

static fc_code read_key(const key_context *k, const cJSON *object, fc_camera_key *key, fc_error *err)
{
    if (!cJSON_IsObject(object))
        return fc_error_set(err, FC_ERR_PARSE, "%s: keyframe %u is not an object { \"frame\": N, \"eye\": [..], ... }",
                            k->name, (unsigned)k->index);
    bool seen[MEMBER_COUNT] = {false};
    for (const cJSON *item = object->child; item; item = item->next) {
        int m = member_of(item->string);
        if (m < 0)
            return fc_error_set(err, FC_ERR_PARSE,
                                "%s: keyframe %u: unknown member \"%s\" (frame, eye, target, up and fov are known)",
                                k->name, (unsigned)k->index, item->string ? item->string : "");
        if (seen[m])
            return key_error(k, err, MEMBER_NAMES[m], "is given twice");
        seen[m] = true;
        fc_code code = read_member(k, m, item, key, err);
        if (code != FC_OK)
            return code;
    }
    for (int m = M_FRAME; m <= M_TARGET; m++)
        if (!seen[m])
            return key_error(k, err, MEMBER_NAMES[m], "is missing");
    /* Compared as the floats the camera carries: 1 and 1.00000001 are one float. */
    if (key->eye[0] == key->target[0] && key->eye[1] == key->target[1] && key->eye[2] == key->target[2])
        return key_error(k, err, "eye", "is the target: the camera needs a direction");
    return FC_OK;
}

/* ---- the file ---- */

static const cJSON *keyframe_array(const cJSON *root, const char *name, fc_error *err)
{
    const cJSON *keys = cJSON_IsObject(root) ? cJSON_GetObjectItemCaseSensitive(root, "keyframes") : root;
    if (!cJSON_IsArray(keys)) {
        fc_error_set(err, FC_ERR_PARSE,
                     "%s: expected an array of keyframes, or an object with a \"keyframes\" array", name);
        return NULL;
    }
    return keys;
}

static fc_code read_keys(const cJSON *keys, const char *name, fc_camera_path *out, fc_error *err)
{
    int n = cJSON_GetArraySize(keys);
    if (n == 0)
        return fc_error_set(err, FC_ERR_PARSE, "%s: no keyframe", name);
    if ((unsigned)n > FC_CAMERA_PATH_MAX_KEYS)
        return fc_error_set(err, FC_ERR_LIMIT, "%s: %d keyframes, at most %u", name, n,
                            (unsigned)FC_CAMERA_PATH_MAX_KEYS);
    out->keys = calloc((size_t)n, sizeof *out->keys);
    if (!out->keys)
        return fc_error_set(err, FC_ERR_NOMEM, "%s: no memory for %d keyframes", name, n);
    for (const cJSON *item = keys->child; item; item = item->next) {
        key_context k = {.name = name, .index = out->count + 1};
        fc_camera_key *key = &out->keys[out->count];
        fc_code code = read_key(&k, item, key, err);
        if (code != FC_OK)
            return code;
        if (out->count > 0 && key->frame <= key[-1].frame)
            return fc_error_set(err, FC_ERR_PARSE,
                                "%s: keyframe %u is at frame %u, not after keyframe %u's frame %u: frames must "
                                "increase",
                                name, (unsigned)k.index, (unsigned)key->frame, (unsigned)out->count,
                                (unsigned)key[-1].frame);
        out->count++;
    }
    return FC_OK;
}

fc_code fc_camera_path_parse(const char *text, size_t size, const char *name, fc_camera_path *out, fc_error *err)
{
    memset(out, 0, sizeof *out);
    if (size > FC_CAMERA_PATH_MAX_BYTES)
        return fc_error_set(err, FC_ERR_LIMIT, "%s: %zu bytes, at most %u", name, size,
                            (unsigned)FC_CAMERA_PATH_MAX_BYTES);
    const char *stop = NULL;
    cJSON *root = cJSON_ParseWithLengthOpts(text, size, &stop, false);
    if (!root)
        return syntax_error(text, size, stop, name, err);
    /* Only white space may follow the value. */
    while (stop && stop < text + size && strchr(" \t\r\n", *stop) && *stop)
        stop++;
    fc_code code = FC_OK;
    if (stop && stop < text + size)
        code = syntax_error(text, size, stop, name, err);
    const cJSON *keys = code == FC_OK ? keyframe_array(root, name, err) : NULL;
    if (code == FC_OK)
        code = keys ? read_keys(keys, name, out, err) : FC_ERR_PARSE;
    cJSON_Delete(root);
    if (code != FC_OK)
        fc_camera_path_free(out);
    return code;
}

fc_code fc_camera_path_load(const char *path, fc_camera_path *out, fc_error *err)
{
    memset(out, 0, sizeof *out);
    uint8_t *text = NULL;
    size_t size = 0;
    fc_code code = fc_read_file(path, FC_CAMERA_PATH_MAX_BYTES, &text, &size, err);
    if (code == FC_OK)
        code = fc_camera_path_parse((const char *)text, size, path, out, err);
    free(text);
    return code;
}

void fc_camera_path_free(fc_camera_path *p)
{
    free(p->keys);
    memset(p, 0, sizeof *p);
}
