/* e2e_scene.c — the benchmark's frame, settings and camera per configuration. */
#include "e2e_scene.h"

#include "fc_frame.h"
#include "scene.h"

/* Small against the lattice spacing (about 1/100 of it at 1M particles). */
#define NUDGE_METRES 1e-4f

fc_code e2e_scene_make(const e2e_config *cfg, e2e_scene *out, fc_error *err)
{
    *out = (e2e_scene){0};
    float spacing;
    fc_code code = bench_scene_drop(cfg->particles, &out->frame, &spacing, err);
    if (code != FC_OK)
        return code;
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
