/* e2e_scene.h — one configuration of fluidcast-e2e-bench and the drop scene,
 * settings and camera it is rendered with. */
#ifndef FC_E2E_SCENE_H
#define FC_E2E_SCENE_H

#include "fluidcast_types.h"

typedef struct e2e_config {
    uint64_t particles;
    uint32_t width, height;
    fc_render_request request;
    int density;             /* the frame carries densities */
    fc_jpeg_subsampling stream_subsampling; /* the streaming viewer's JPEG chroma */
} e2e_config;

typedef struct e2e_scene {
    fc_frame frame;          /* the drop scene (bench/scene.h) */
    fc_settings settings;    /* defaults with the radius a simulation would know: no server-side estimate */
    fc_camera camera;
} e2e_scene;

fc_code e2e_scene_make(const e2e_config *cfg, e2e_scene *out, fc_error *err);
void e2e_scene_free(e2e_scene *s);

/* Moves every particle a little along z (up on odd steps, down on even ones),
 * so each frame sent is new and the scene stays where it is. */
void e2e_scene_nudge(e2e_scene *s, uint64_t step);

#endif
