/* legend.c — the colour bar, its ticks and labels. */
#include "legend.h"

#include <stdio.h>

#include "fc_colormap.h"
#include "fc_error.h"
#include "legend_text.h"

#define TICKS 5
/* The background under the legend keeps this share of its brightness, so
 * white text reads over any scene. */
#define BACKGROUND_KEPT 0.35f

typedef struct layout {
    fc_legend_box box;
    int margin, line;
    int bar_x, bar_y, bar_w, bar_h;   /* the bar, top = the range's max */
    int label_x;
} layout;

static int clamp_int(int v, int lo, int hi)
{
    return v < lo ? lo : v > hi ? hi : v;
}

static float tick_value(const fc_settings *s, int k)
{
    return s->color_range[0] + (s->color_range[1] - s->color_range[0]) * (float)k / (float)(TICKS - 1);
}

static void tick_label(const fc_settings *s, int k, char text[32])
{
    snprintf(text, 32, "%.3g", (double)tick_value(s, k));
}

static const char *attribute_title(const fc_settings *s)
{
    return s->color_by == FC_COLOR_BY_DENSITY ? "density" : "speed";
}

/* The box at the top-right corner, as large as its title, bar and widest label need. */
static layout place(fc_legend_font *font, const fc_settings *s, int width, int height, uint32_t font_px)
{
    layout l;
    l.line = fc_legend_line_height(font);
    l.margin = clamp_int((int)font_px / 2, 3, 16);
    l.bar_w = (int)font_px;
    l.bar_h = clamp_int(height * 45 / 100, 3 * l.line, height);
    int widest = 0;
    for (int k = 0; k < TICKS; k++) {
        char text[32];
        tick_label(s, k, text);
        int w = fc_legend_text_width(font, text);
        widest = w > widest ? w : widest;
    }
    int inner = l.bar_w + 2 * l.margin + widest;
    int title = fc_legend_text_width(font, attribute_title(s));
    inner = title > inner ? title : inner;
    int box_w = inner + 2 * l.margin, box_h = 2 * l.margin + l.line + l.margin / 2 + l.bar_h + l.line;
    l.box.x1 = width - l.margin;
    l.box.x0 = clamp_int(l.box.x1 - box_w, 0, width);
    l.box.y0 = l.margin < height ? l.margin : 0;
    l.box.y1 = clamp_int(l.box.y0 + box_h, 0, height);
    l.bar_x = l.box.x0 + l.margin;
    l.bar_y = l.box.y0 + l.margin + l.line + l.margin / 2 + l.line / 2;
    l.label_x = l.bar_x + l.bar_w + 2 * l.margin;
    return l;
}

/* Sets pixel (x, y) to rgb (sRGB in [0, 1]: stored as is in 8-bit images, linearised in float ones). */
static void put_pixel(fc_image *img, int x, int y, const float rgb[3])
{
    size_t at = ((size_t)y * img->width + (size_t)x) * img->channels;
    for (int c = 0; c < 3; c++) {
        if (img->type == FC_PIXEL_U8)
            ((uint8_t *)img->pixels)[at + c] = (uint8_t)(rgb[c] * 255.0f + 0.5f);
        else
            ((float *)img->pixels)[at + c] = fc_srgb_to_linear(rgb[c]);
    }
}

static void darken(fc_image *img, const fc_legend_box *b)
{
    for (int y = b->y0; y < b->y1; y++)
        for (int x = b->x0; x < b->x1; x++) {
            size_t at = ((size_t)y * img->width + (size_t)x) * img->channels;
            for (int c = 0; c < 3; c++) {
                if (img->type == FC_PIXEL_U8)
                    ((uint8_t *)img->pixels)[at + c] = (uint8_t)((float)((uint8_t *)img->pixels)[at + c] * BACKGROUND_KEPT);
                else
                    ((float *)img->pixels)[at + c] *= BACKGROUND_KEPT;
            }
        }
}

static bool inside(const fc_legend_box *b, int x, int y)
{
    return x >= b->x0 && x < b->x1 && y >= b->y0 && y < b->y1;
}

/* The bar, the range's max at its top, and a tick mark at each label. */
static void draw_bar(fc_image *img, const fc_settings *s, const layout *l)
{
    const float white[3] = {1.0f, 1.0f, 1.0f};
    for (int row = 0; row < l->bar_h; row++) {
        float rgb[3];
        fc_colormap_srgb(s->colormap, 1.0f - ((float)row + 0.5f) / (float)l->bar_h, rgb);
        for (int x = l->bar_x; x < l->bar_x + l->bar_w + l->margin; x++) {
            bool tick = false;
            for (int k = 0; k < TICKS; k++)
                tick = tick || row == (l->bar_h - 1) * (TICKS - 1 - k) / (TICKS - 1);
            bool on_bar = x < l->bar_x + l->bar_w;
            if ((on_bar || tick) && inside(&l->box, x, l->bar_y + row))
                put_pixel(img, x, l->bar_y + row, on_bar ? rgb : white);
        }
    }
}

static void draw_labels(fc_legend_font *font, fc_image *img, const fc_settings *s, const layout *l)
{
    const int clip[4] = {l->box.x0, l->box.x1, l->box.y0, l->box.y1};
    fc_legend_text_draw(font, img, l->box.x0 + l->margin, l->box.y0 + l->margin, attribute_title(s), clip);
    for (int k = 0; k < TICKS; k++) {
        char text[32];
        tick_label(s, k, text);
        int row = l->bar_y + (l->bar_h - 1) * (TICKS - 1 - k) / (TICKS - 1);
        fc_legend_text_draw(font, img, l->label_x, row - l->line / 2, text, clip);
    }
}

fc_code fc_legend_draw(fc_image *img, const fc_settings *s, const char *font_path, fc_legend_box *box,
                       fc_error *err)
{
    uint32_t font_px = (uint32_t)clamp_int((int)img->height / 30, 10, 28);
    fc_legend_font *font = NULL;
    fc_code code = fc_legend_font_open(font_path, font_px, &font, err);
    if (code != FC_OK)
        return code;
    layout l = place(font, s, (int)img->width, (int)img->height, font_px);
    *box = l.box;
    darken(img, &l.box);
    draw_bar(img, s, &l);
    draw_labels(font, img, s, &l);
    fc_legend_font_close(font);
    return FC_OK;
}
