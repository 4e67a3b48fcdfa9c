/* e2e_scene.c — the benchmark's frame, settings and camera per configuration. */
#include "e2e_scene.h"

#include <stdlib.h>

#include "fc_error.h"
#include "fc_frame.h"
#include "scene.h"

/* Small against the lattice spacing (about 1/100 of it at 1M particles). */
#define NUDGE_METRES 1e-4f
/* Water's rest density, and the spread an SPH solver's densities show around it. */
#define REST_DENSITY 1000.0f
#define DENSITY_SPREAD 0.05f

/* Densities as an SPH code would send them: around the rest density, varying
 * from particle to particle, so that sorting by them is real work. */
static fc_code add_densities(fc_frame *frame, fc_error *err)
{
    frame->density = malloc((size_t)frame->count * sizeof *frame->density);
    if (!frame->density)
        return fc_error_set(err, FC_ERR_NOMEM, "no memory for %llu densities", (unsigned long long)frame->count);
    uint32_t state = 2463534242u;   /* xorshift32: the same densities every run */
    for (uint64_t i = 0; i < frame->count; i++) {
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        float unit = (float)(state >> 8) / (float)(1u << 24);
        frame->density[i] = REST_DENSITY * (1.0f + DENSITY_SPREAD * (2.0f * unit - 1.0f));
    }
    return FC_OK;
}

fc_code e2e_scene_make(const e2e_config *cfg, e2e_scene *out, fc_error *err)
{
    *out = (e2e_scene){0};
    float spacing;
    fc_code code = bench_scene_drop(cfg->particles, &out->frame, &spacing, err);
    if (code == FC_OK && cfg->density)
        code = add_densities(&out->frame, err);
    if (code != FC_OK) {
        fc_frame_free(&out->frame);
        return code;
    }
    fc_settings_default(&out->settings);
    out->settings.radius = BENCH_SCENE_RADIUS_PER_SPACING * spacing;
    bench_scene_drop_camera(cfg->width, cfg->height, &out->camera);
    return FC_OK;
}

void e2e_scene_free(e2e_scene *s)
{
    fc_frame_free(&s->frame);
}

void e2e_scene_nudge(e2e_scene *s, uint64_t step)
{
    float dz = step % 2 ? NUDGE_METRES : -NUDGE_METRES;
    for (uint64_t i = 0; i < s->frame.count; i++)
        s->frame.positions[3 * i + 2] += dz;
}
