/*
 * False-colour heat maps of block maps (relative differences, z values),
 * with an optional colour bar labelled in the built-in font.
 */
#include <math.h>
#include <stdio.h>
#include "image/font.h"
#include "image/heatcolour.h"
#include "materia/tools/imgcmp.h"

/* An inferno-like scale (after the matplotlib colour map of van der Walt and
 * Smith: dark, perceptually ordered, legible in grey): sRGB stops at 0,
 * 1/4, 1/2, 3/4, 1. */
static const float stops[5][3] = {
    {0, 0, 4}, {87, 16, 110}, {188, 55, 84}, {249, 142, 9}, {252, 255, 164}};

void mt__heat_colour(double t, float *rgb)
{
    double s;
    int i, c;
    if (!(t < 1)) t = 1;
    if (t < 0) t = 0;
    s = t * 4;
    i = s >= 4 ? 3 : (int)s;
    for (c = 0; c < 3; ++c) {
        double v = stops[i][c] + (s - i) * (stops[i + 1][c] - stops[i][c]);
        rgb[c] = mt_srgb_to_linear((float)(v / 255));
    }
}

/* Heights of the colour bar's parts, in pixels. */
enum { BAR_GAP = 2, BAR_STRIP = 6, BAR_HEIGHT = BAR_GAP + BAR_STRIP + BAR_GAP + MT__FONT_H + BAR_GAP };

static void draw_bar(mt_image *out, int y0, double vmax)
{
    static const float white[3] = {1, 1, 1};
    char label[32];
    int x, y;
    for (x = 0; x < out->width; ++x) {
        float rgb[3];
        mt__heat_colour(out->width > 1 ? (double)x / (out->width - 1) : 1, rgb);
        for (y = y0 + BAR_GAP; y < y0 + BAR_GAP + BAR_STRIP; ++y) {
            float *p = out->data + ((size_t)y * (size_t)out->width + (size_t)x) * 3;
            p[0] = rgb[0];
            p[1] = rgb[1];
            p[2] = rgb[2];
        }
    }
    y = y0 + 2 * BAR_GAP + BAR_STRIP;
    mt__draw_text(out, 1, y, "0", 1, white);
    snprintf(label, sizeof label, "%.3g", vmax);
    mt__draw_text(out, out->width - 1 - mt__text_width(label, 1), y, label, 1, white);
}

mt_status mt_imgcmp_heatmap(const mt_image *blocks, int block, int width, int height,
                            double vmax, int bar, mt_image *out, mt_error *err)
{
    mt_status st;
    int x, y, c, nc;
    mt_error_clear(err);
    if (!blocks || !blocks->data || !out)
        return mt_error_set(err, MT_ERR_INVALID, "mt_imgcmp_heatmap: no block map or output");
    if (block < 1 || width < 1 || height < 1 ||
        blocks->width != (width + block - 1) / block ||
        blocks->height != (height + block - 1) / block)
        return mt_error_set(err, MT_ERR_INVALID,
                            "a block map of %d x %d does not cover %d x %d pixels in blocks of %d",
                            blocks->width, blocks->height, width, height, block);
    if (!(vmax > 0) || !isfinite(vmax))
        return mt_error_param(err, MT_ERR_INVALID, "vmax",
                              "the top of the scale must be positive, not %g", vmax);
    if ((st = mt_image_create(out, width, height + (bar ? BAR_HEIGHT : 0), 3, err)) != MT_OK)
        return st;
    nc = blocks->channels == 1 ? 1 : 3;
    for (y = 0; y < height; ++y)
        for (x = 0; x < width; ++x) {
            const float *b = blocks->data + ((size_t)(y / block) * (size_t)blocks->width +
                                             (size_t)(x / block)) * (size_t)blocks->channels;
            double v = 0;
            for (c = 0; c < nc; ++c)
                if (!(fabs(b[c]) <= v)) v = fabs(b[c]);
            mt__heat_colour(v / vmax, out->data + ((size_t)y * (size_t)width + (size_t)x) * 3);
        }
    if (bar) draw_bar(out, height, vmax);
    return MT_OK;
}
