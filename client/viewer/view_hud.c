/* view_hud.c — the HUD line. */
#include "view_hud.h"

#include <stdio.h>

void fc_view_hud_count(fc_view_hud *hud, double now_ms)
{
    if (hud->window_images == 0)
        hud->window_start_ms = now_ms;
    hud->window_images++;
    double span = now_ms - hud->window_start_ms;
    if (span >= 500.0) {
        hud->fps = (hud->window_images - 1) * 1000.0 / span;
        hud->window_images = 1;
        hud->window_start_ms = now_ms;
    }
}

static double stage(const fc_view_image *img, fc_stage s)
{
    return img->stage_ms[s] < 0.0f ? 0.0 : (double)img->stage_ms[s];
}

void fc_view_hud_line(const fc_view_hud *hud, const fc_view_image *img, const char *what, fc_sm_mode mode,
                      const char *smoothing, char *out, size_t size)
{
    char rtt[32] = "-";
    if (img->round_trip_ms >= 0.0)
        snprintf(rtt, sizeof rtt, "%.0f ms", img->round_trip_ms);
    snprintf(out, size,
             "fluidcast view | %s | %.1f fps | %ux%u%s | server %.1f ms (depth %.1f, smooth %.1f, composite %.1f, "
             "encode %.1f) | round trip %s | %s | %s",
             what, hud->fps, (unsigned)img->width, (unsigned)img->height, img->preview ? " preview" : "",
             stage(img, FC_STAGE_TOTAL), stage(img, FC_STAGE_DEPTH), stage(img, FC_STAGE_SMOOTHING),
             stage(img, FC_STAGE_COMPOSITE), stage(img, FC_STAGE_ENCODE), rtt,
             mode == FC_SM_MODE_FLY ? "fly" : "orbit", smoothing);
}
