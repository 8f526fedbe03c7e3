/*
 * The picture of a chi-square check (--plots): its cells, laid where the
 * implementation's pilot samples fell (cells.c), drawn one row of cos theta
 * per band (+1 at the top) and each row's cells side by side at equal
 * widths, so that a sharp lobe fills the picture instead of one cell of a
 * sphere: the expected counts, the histogram of the samples and
 * |o - e| / sqrt(e), each with its colour scale, under a title naming the
 * configuration, the check, wo and the p-value, and a line saying which
 * directions the rows cover.
 */
#include <stdio.h>
#include <string.h>
#include "core.h"
#include "image/font.h"
#include "materia/tools/imgcmp.h"

#define GAP 12  /* between panels */
#define LINE (MT__FONT_H + 4)
#define PANEL_W 252
#define DEG (180 / 3.14159265358979323846)

static void fill(mt_image *img, const float *rgb)
{
    size_t i, n = (size_t)img->width * (size_t)img->height;
    for (i = 0; i < n; ++i) memcpy(img->data + 3 * i, rgb, 3 * sizeof *rgb);
}

static void blit(mt_image *dst, const mt_image *src, int x0, int y0)
{
    int y;
    for (y = 0; y < src->height && y0 + y < dst->height; ++y) {
        int w = src->width;
        if (x0 + w > dst->width) w = dst->width - x0;
        if (w > 0)
            memcpy(dst->data + ((size_t)(y0 + y) * (size_t)dst->width + (size_t)x0) * 3,
                   src->data + (size_t)y * (size_t)src->width * 3, (size_t)w * 3 * sizeof(float));
    }
}

int cf_plot_cells(const char *path, const char *title, const char *subtitle, const char *expected_label,
                  const cf_layout *l, const long *counts, const double *pdfc, long n, mt_error *err)
{
    static const float white[3] = {1, 1, 1}, grey[3] = {0.02f, 0.02f, 0.02f};
    const char *labels[3];
    mt_image maps[3], panels[3], out;
    double vmax[3] = {0, 0, 3};
    int k, r, c, w, h, band = 240 / (l->nrow > 0 ? l->nrow : 1), ph;
    char rows[300];
    mt_status st = MT_OK;
    memset(maps, 0, sizeof maps);
    memset(panels, 0, sizeof panels);
    memset(&out, 0, sizeof out);
    labels[0] = expected_label;
    labels[1] = "samples";
    labels[2] = "|o - e| / sqrt(e)";
    if (band < 3) band = 3;
    ph = band * l->nrow;
    for (k = 0; k < 3; ++k)
        if ((st = mt_image_create(&maps[k], PANEL_W, ph, 1, err))) goto done;
    for (r = 0; r < l->nrow; ++r) {
        int a = l->first[r], b = l->first[r + 1], y0 = (l->nrow - 1 - r) * band; /* cos theta = +1 at the top */
        for (c = a; c < b; ++c) {
            double e = pdfc[c] * n, o = (double)counts[c], d = e > 0 ? (o - e) / sqrt(e) : (o > 0 ? 1e3 : 0);
            int x0 = PANEL_W * (c - a) / (b - a), x1 = PANEL_W * (c - a + 1) / (b - a), x, y;
            double v[3];
            v[0] = e;
            v[1] = o;
            v[2] = fabs(d);
            for (k = 0; k < 3; ++k) vmax[k] = fmax(vmax[k], v[k]);
            for (y = y0; y < y0 + band; ++y)
                for (x = x0; x < x1; ++x)
                    for (k = 0; k < 3; ++k)
                        /* a line between cells, so that their layout shows */
                        maps[k].data[(size_t)y * PANEL_W + (size_t)x] = (float)((x == x0 && x0 > 0) || y == y0 ? 0 : v[k]);
        }
    }
    /* expected and observed on one scale, so that equal means equal colour */
    vmax[0] = vmax[1] = fmax(fmax(vmax[0], vmax[1]), 1);
    for (k = 0; k < 3; ++k)
        if ((st = mt_imgcmp_heatmap(&maps[k], 1, PANEL_W, ph, vmax[k], 1, &panels[k], err))) goto done;
    /* where the rows are: the zoom, in degrees from the normal */
    snprintf(rows, sizeof rows, "%d rows of cos theta (a band each, +1 at the top), %d cells at equal widths; top row theta "
             "0..%.4g deg, next %.4g..%.4g, bottom %.4g..180", l->nrow, l->ncell, acos(l->z[l->nrow - 1]) * DEG,
             acos(fmin(1, l->z[l->nrow - 1])) * DEG, acos(l->z[l->nrow > 1 ? l->nrow - 2 : 0]) * DEG, acos(l->z[1]) * DEG);
    w = 3 * panels[0].width + 4 * GAP;
    if (mt__text_width(title, 1) + 2 * GAP > w) w = mt__text_width(title, 1) + 2 * GAP;
    if (mt__text_width(subtitle, 1) + 2 * GAP > w) w = mt__text_width(subtitle, 1) + 2 * GAP;
    if (mt__text_width(rows, 1) + 2 * GAP > w) w = mt__text_width(rows, 1) + 2 * GAP;
    h = 3 * LINE + panels[0].height + LINE + GAP;
    if ((st = mt_image_create(&out, w, h, 3, err))) goto done;
    fill(&out, grey);
    mt__draw_text(&out, GAP, 4, title, 1, white);
    mt__draw_text(&out, GAP, 4 + LINE, subtitle, 1, white);
    for (k = 0; k < 3; ++k) {
        int x = GAP + k * (panels[0].width + GAP);
        mt__draw_text(&out, x, 4 + 2 * LINE + 2, labels[k], 1, white);
        blit(&out, &panels[k], x, 3 * LINE + 4);
    }
    mt__draw_text(&out, GAP, 3 * LINE + 4 + panels[0].height + 3, rows, 1, white);
    st = mt_image_write(path, &out, NULL, 0, err);
done:
    for (k = 0; k < 3; ++k) {
        mt_image_destroy(&maps[k]);
        mt_image_destroy(&panels[k]);
    }
    mt_image_destroy(&out);
    return st ? -1 : 0;
}
