/* cli_particles.c — see cli_particles.h. */
#include "cli_particles.h"

#include "cli_report.h"
#include "fc_frame.h"
#include "particle_reader.h"

int fc_cli_load_particles(const char *path, const fc_read_options *options, fc_frame *frame)
{
    fc_error err;
    if (fc_read_particles_with(path, options, frame, &err) != FC_OK)
        return fc_cli_fail(FC_EXIT_INPUT, "%s", err.message);
    if (frame->count == 0)
        return fc_cli_fail(FC_EXIT_INPUT, "%s holds no particles", path);
    if (fc_frame_validate(frame, &err) != FC_OK)
        return fc_cli_fail(FC_EXIT_INPUT, "%s: %s", path, err.message);
    return FC_EXIT_OK;
}
