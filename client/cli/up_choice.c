/* up_choice.c — see up_choice.h. */
#include "up_choice.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "up_axis.h"

#define OVERRIDE_HINT "--up to override"
/* The view counts as along the up axis when the angle between them is below
 * about 0.5 degrees; fc_camera_validate's own limit is tighter, and a picture
 * rolled by chance that close to the pole is no better. */
#define MIN_UP_SINE 0.01

fc_code fc_up_choose(bool has_up, const float given[3], const fc_frame *frame, fc_up_choice *out, fc_error *err)
{
    memset(out, 0, sizeof *out);
    if (has_up) {
        memcpy(out->up, given, sizeof out->up);
        out->given = true;
        return FC_OK;
    }
    fc_up_guess guess;
    fc_code code = fc_up_axis_guess(frame, &guess, err);
    if (code != FC_OK)
        return code;
    fc_up_axis_vector(&guess, out->up);
    snprintf(out->note, sizeof out->note, "%s (%s; " OVERRIDE_HINT ")", fc_up_axis_name(guess.axis, guess.sign),
             guess.from_particles ? "guessed from the particles" : "default: no floor among the particles");
    return FC_OK;
}

/* Sine of the angle between the view and the up vector. */
static double view_up_sine(const float eye[3], const float target[3], const float up[3])
{
    double view[3], side[3];
    for (int k = 0; k < 3; k++)
        view[k] = (double)target[k] - eye[k];
    side[0] = view[1] * up[2] - view[2] * up[1];
    side[1] = view[2] * up[0] - view[0] * up[2];
    side[2] = view[0] * up[1] - view[1] * up[0];
    double view_len = sqrt(view[0] * view[0] + view[1] * view[1] + view[2] * view[2]);
    double side_len = sqrt(side[0] * side[0] + side[1] * side[1] + side[2] * side[2]);
    return view_len > 0 ? side_len / view_len : 1.0;   /* |up| is 1: a guess is a unit axis */
}

void fc_up_choice_fit_view(fc_up_choice *c, const float eye[3], const float target[3])
{
    if (c->given || view_up_sine(eye, target, c->up) >= MIN_UP_SINE)
        return;
    const float z[3] = {0, 0, 1}, y[3] = {0, 1, 0};
    const float *fallback = view_up_sine(eye, target, z) >= MIN_UP_SINE ? z : y;
    char chosen[4];
    snprintf(chosen, sizeof chosen, "%.2s", c->note);   /* the note starts with the axis, e.g. "+y" */
    snprintf(c->note, sizeof c->note, "%s (the view looks along %s; " OVERRIDE_HINT ")", fallback == z ? "+z" : "+y",
             chosen);
    memcpy(c->up, fallback, sizeof c->up);
}
