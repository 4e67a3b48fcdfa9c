/* fuzz_wire_settings.c — libFuzzer target for fc_wire_read_settings: the input
 * is one SETTINGS payload, applied onto the default settings.
 *
 * Checked beyond memory safety: a refusal leaves the settings exactly as they
 * were (the decoder is atomic), an accepted payload gives valid settings, and
 * those settings survive an encode/decode round trip unchanged. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fc_frame.h"
#include "fuzz_check.h"
#include "wire.h"

/* Every field of fc_settings: a key the codec forgets to carry shows up here.
 * The size check makes a field added later fail the build until it is compared. */
_Static_assert(sizeof(fc_settings) == 38 * 4, "fc_settings changed: compare its new fields in settings_equal");
static bool settings_equal(const fc_settings *a, const fc_settings *b)
{
    bool equal = a->radius == b->radius && a->smoothing == b->smoothing && a->iterations == b->iterations &&
                 a->filter_radius == b->filter_radius && a->smooth_scale == b->smooth_scale && a->ior == b->ior &&
                 a->refraction == b->refraction && a->specular == b->specular && a->shininess == b->shininess &&
                 a->thickness_scale == b->thickness_scale && a->thickness_blur == b->thickness_blur &&
                 a->noise == b->noise && a->foam == b->foam && a->foam_tau == b->foam_tau &&
                 a->foam_decay == b->foam_decay && a->density_threshold == b->density_threshold &&
                 a->kernel == b->kernel && a->shadow == b->shadow && a->exposure == b->exposure &&
                 a->color_by == b->color_by && a->colormap == b->colormap &&
                 a->color_range[0] == b->color_range[0] && a->color_range[1] == b->color_range[1] &&
                 a->jpeg_subsampling == b->jpeg_subsampling && a->spray_neighbours == b->spray_neighbours &&
                 a->surface == b->surface && a->surface_cell == b->surface_cell &&
                 a->surface_kernel == b->surface_kernel && a->surface_smoothing == b->surface_smoothing &&
                 a->contact_shadow == b->contact_shadow && a->depth_dimming == b->depth_dimming &&
                 a->aerated_foam == b->aerated_foam;
    for (int c = 0; c < 3; c++)
        equal = equal && a->fluid_color[c] == b->fluid_color[c] && a->absorption[c] == b->absorption[c];
    return equal;
}

static void check_round_trip(const fc_settings *decoded)
{
    fc_error err = {FC_OK, ""};
    fc_buf encoded;
    fc_buf_init(&encoded);
    FUZZ_REQUIRE(fc_wire_write_settings(&encoded, 0, decoded, &err) == FC_OK, "encoding failed: %s", err.message);
    fc_settings again;
    fc_settings_default(&again);
    fc_code code = fc_wire_read_settings(encoded.data + FC_WIRE_HEADER_SIZE, encoded.len - FC_WIRE_HEADER_SIZE,
                                         &again, &err);
    FUZZ_REQUIRE(code == FC_OK, "re-encoded settings refused: %s", err.message);
    FUZZ_REQUIRE(settings_equal(&again, decoded), "settings changed in an encode/decode round trip");
    fc_buf_free(&encoded);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    /* A copy of exactly the payload, so that AddressSanitizer sees any read past it. */
    uint8_t *payload = malloc(size);
    FUZZ_REQUIRE(payload != NULL || size == 0, "cannot copy %zu bytes", size);
    if (size > 0)
        memcpy(payload, data, size);

    fc_settings defaults, settings;
    fc_settings_default(&defaults);
    settings = defaults;
    fc_error err = {FC_OK, ""};
    fc_code code = fc_wire_read_settings(payload, size, &settings, &err);
    if (code == FC_OK) {
        FUZZ_REQUIRE(fc_settings_validate(&settings, &err) == FC_OK, "accepted invalid settings: %s", err.message);
        check_round_trip(&settings);
    } else {
        fuzz_require_reported(code, &err);
        FUZZ_REQUIRE(code == FC_ERR_MALFORMED || code == FC_ERR_INVALID_VALUE, "code %d: %s", (int)code,
                     err.message);
        FUZZ_REQUIRE(settings_equal(&settings, &defaults), "a refused payload changed the settings");
    }
    free(payload);
    return 0;
}
