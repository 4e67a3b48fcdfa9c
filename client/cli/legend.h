/* legend.h — `fluidcast snapshot --legend`: a colour bar of the colormap with
 * the attribute's name and five tick labels over the colour range, drawn
 * into the decoded image in the client (the server's image stays the
 * fluid alone), in a darkened box at its top-right corner. */
#ifndef FC_LEGEND_H
#define FC_LEGEND_H

#include "fluidcast_types.h"
#include "image.h"

/* Where the legend lies: columns [x0, x1), rows [y0, y1) from the top. */
typedef struct fc_legend_box {
    int x0, y0, x1, y1;
} fc_legend_box;

/* Draws the legend of s (color_by, colormap, color_range) into `img` (RGBA,
 * 8-bit sRGB or float linear, rows top to bottom) with the TrueType font at
 * `font_path`; every changed pixel lies in *box. FC_ERR_IO when the font
 * cannot be read. */
fc_code fc_legend_draw(fc_image *img, const fc_settings *s, const char *font_path, fc_legend_box *box,
                       fc_error *err);

#endif
