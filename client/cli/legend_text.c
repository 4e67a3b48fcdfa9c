/* legend_text.c — FreeType glyphs blended into an RGBA image. */
#include "legend_text.h"

#include <ft2build.h>
#include FT_FREETYPE_H
#include <stdlib.h>

#include "fc_error.h"

struct fc_legend_font {
    FT_Library library;
    FT_Face face;
};

fc_code fc_legend_font_open(const char *path, uint32_t pixels, fc_legend_font **font, fc_error *err)
{
    *font = calloc(1, sizeof **font);
    if (!*font)
        return fc_error_set(err, FC_ERR_NOMEM, "out of memory for the legend's font");
    fc_legend_font *f = *font;
    if (FT_Init_FreeType(&f->library) != 0) {
        fc_legend_font_close(f);
        *font = NULL;
        return fc_error_set(err, FC_ERR_IO, "FreeType could not start");
    }
    if (FT_New_Face(f->library, path, 0, &f->face) != 0 || FT_Set_Pixel_Sizes(f->face, 0, pixels) != 0) {
        fc_legend_font_close(f);
        *font = NULL;
        return fc_error_set(err, FC_ERR_IO, "cannot read the legend's font %s (Debian: fonts-dejavu-core)", path);
    }
    return FC_OK;
}

void fc_legend_font_close(fc_legend_font *font)
{
    if (!font)
        return;
    if (font->face)
        FT_Done_Face(font->face);
    if (font->library)
        FT_Done_FreeType(font->library);
    free(font);
}

int fc_legend_text_width(fc_legend_font *font, const char *text)
{
    long width = 0;
    for (const char *c = text; *c; c++)
        if (FT_Load_Char(font->face, (unsigned char)*c, FT_LOAD_DEFAULT) == 0)
            width += font->face->glyph->advance.x >> 6;
    return (int)width;
}

int fc_legend_line_height(const fc_legend_font *font)
{
    const FT_Size_Metrics *m = &font->face->size->metrics;
    return (int)((m->ascender - m->descender) >> 6);
}

/* Blends white over pixel (x, y) by `coverage` in [0, 1]. */
static void blend_white(fc_image *img, int x, int y, float coverage)
{
    size_t at = ((size_t)y * img->width + (size_t)x) * img->channels;
    for (uint32_t c = 0; c < 3 && c < img->channels; c++) {
        if (img->type == FC_PIXEL_U8) {
            uint8_t *p = (uint8_t *)img->pixels + at + c;
            *p = (uint8_t)((float)*p + coverage * (255.0f - (float)*p) + 0.5f);
        } else {
            float *p = (float *)img->pixels + at + c;
            *p += coverage * (1.0f - *p);
        }
    }
}

static void draw_glyph(const FT_GlyphSlot g, fc_image *img, int left, int top, const int clip[4])
{
    const FT_Bitmap *b = &g->bitmap;
    for (unsigned row = 0; row < b->rows; row++)
        for (unsigned col = 0; col < b->width; col++) {
            int x = left + (int)col, y = top + (int)row;
            if (x < clip[0] || x >= clip[1] || y < clip[2] || y >= clip[3])
                continue;
            uint8_t coverage = b->buffer[(size_t)row * (size_t)b->pitch + col];
            if (coverage)
                blend_white(img, x, y, (float)coverage / 255.0f);
        }
}

void fc_legend_text_draw(fc_legend_font *font, fc_image *img, int x, int top, const char *text, const int clip[4])
{
    int baseline = top + (int)(font->face->size->metrics.ascender >> 6);
    for (const char *c = text; *c; c++) {
        if (FT_Load_Char(font->face, (unsigned char)*c, FT_LOAD_RENDER) != 0)
            continue;
        FT_GlyphSlot g = font->face->glyph;
        draw_glyph(g, img, x + g->bitmap_left, baseline - g->bitmap_top, clip);
        x += (int)(g->advance.x >> 6);
    }
}
