/* e2e_request.c — the request/response half of fluidcast-e2e-bench. */
#include "e2e_request.h"

/* Sends the nudged frame and asks for its image; the time covers both. */
static fc_code timed_request(fc_client *client, e2e_scene *scene, const e2e_config *cfg, uint64_t step,
                             fc_image_result *img, double *ms, fc_error *err)
{
    e2e_scene_nudge(scene, step);
    double start = e2e_now_ms();
    fc_code code = fc_client_send_frame(client, &scene->frame, err);
    if (code == FC_OK)
        code = fc_client_render(client, &cfg->request, img, err);
    *ms = e2e_now_ms() - start;
    return code;
}

static void add_stages(double sum[FC_STAGE_COUNT], int measured[FC_STAGE_COUNT], const fc_image_result *img)
{
    for (int s = 0; s < FC_STAGE_COUNT; s++)
        if (img->stage_ms[s] >= 0) {
            sum[s] += img->stage_ms[s];
            measured[s]++;
        }
}

static fc_code timed_requests(fc_client *client, e2e_scene *scene, const e2e_config *cfg, int requests,
                              e2e_samples *samples, e2e_request_result *out, fc_error *err)
{
    double stage_sum[FC_STAGE_COUNT] = {0}, bytes = 0;
    int measured[FC_STAGE_COUNT] = {0};
    for (int i = 0; i < requests; i++) {
        fc_image_result img = {0};
        double ms;
        fc_code code = timed_request(client, scene, cfg, (uint64_t)i + 1, &img, &ms, err);
        if (code == FC_OK) {
            add_stages(stage_sum, measured, &img);
            bytes += (double)img.size;
            code = e2e_samples_add(samples, ms, err);
        }
        fc_image_result_free(&img);
        if (code != FC_OK)
            return code;
        out->answered++;
    }
    for (int s = 0; s < FC_STAGE_COUNT; s++)
        out->stage_ms[s] = measured[s] ? stage_sum[s] / measured[s] : -1;
    out->image_kib = out->answered ? bytes / out->answered / 1024.0 : 0;
    return FC_OK;
}

fc_code e2e_run_requests(fc_client *client, const e2e_config *cfg, int requests, e2e_request_result *out,
                         fc_error *err)
{
    *out = (e2e_request_result){0};
    e2e_scene scene;
    fc_code code = e2e_scene_make(cfg, &scene, err);
    if (code != FC_OK)
        return code;
    e2e_samples samples = {0};
    fc_image_result warmup = {0};
    double ms;
    if ((code = fc_client_set_settings(client, &scene.settings, err)) == FC_OK &&
        (code = fc_client_set_camera(client, &scene.camera, err)) == FC_OK &&
        (code = timed_request(client, &scene, cfg, 0, &warmup, &ms, err)) == FC_OK)
        code = timed_requests(client, &scene, cfg, requests, &samples, out, err);
    fc_image_result_free(&warmup);
    e2e_latency_summarize(&samples, &out->latency);
    e2e_samples_free(&samples);
    e2e_scene_free(&scene);
    return code;
}
