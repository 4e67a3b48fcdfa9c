/* legend_text.h — text drawn into an RGBA image with FreeType (a TrueType
 * font from a file, Debian's fonts-dejavu-core by default), for the legend. */
#ifndef FC_LEGEND_TEXT_H
#define FC_LEGEND_TEXT_H

#include <stdint.h>

#include "fluidcast_types.h"
#include "image.h"

typedef struct fc_legend_font fc_legend_font;

/* Opens the font at `path` for glyphs `pixels` high. FC_ERR_IO naming the
 * file when FreeType cannot read it. */
fc_code fc_legend_font_open(const char *path, uint32_t pixels, fc_legend_font **font, fc_error *err);
void fc_legend_font_close(fc_legend_font *font);

/* Width in pixels of `text` drawn with the font. */
int fc_legend_text_width(fc_legend_font *font, const char *text);

/* Height of a line of text: ascent plus descent, in pixels. */
int fc_legend_line_height(const fc_legend_font *font);

/* Draws `text` in white with its top-left at (x, top), blending by the glyph
 * coverage (sRGB values for 8-bit images, linear for float ones); pixels
 * outside [clip_x0, clip_x1) x [clip_y0, clip_y1) are left alone. */
void fc_legend_text_draw(fc_legend_font *font, fc_image *img, int x, int top, const char *text, const int clip[4]);

#endif
