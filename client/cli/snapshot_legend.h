/* snapshot_legend.h — --legend on the image the server sent: decoded,
 * the legend drawn (legend.h), encoded again in the same format. */
#ifndef FC_SNAPSHOT_LEGEND_H
#define FC_SNAPSHOT_LEGEND_H

#include "fluidcast.h"
#include "legend.h"

/* Replaces image's bytes with the same image with the legend of `settings`
 * drawn in; *box is where. JPEG is encoded again at `quality`. */
fc_code fc_snapshot_add_legend(fc_image_result *image, const fc_settings *settings, uint32_t quality,
                               fc_legend_box *box, fc_error *err);

#endif
