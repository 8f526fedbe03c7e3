/*
 * The picture of a chi-square check (--plots): over the sphere in the
 * test's cells (phi across, cos theta down from +1 at the top), the
 * expected counts, the histogram of the samples and |o - e| / sqrt(e) side
 * by side, each with its colour scale, under a title naming the
 * configuration, the check, wo and the p-value.
 */
#include <stdio.h>
#include <string.h>
#include "image/font.h"
#include "impl.h"
#include "materia/tools/imgcmp.h"

#define GAP 12   /* between panels */
#define LINE (MT__FONT_H + 4)

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

int cf_impl_plot(const char *path, const char *title, const char *subtitle, const char *expected_label,
                 const cf_config *cfg, const long *counts, const double *pdfc, long n, mt_error *err)
{
    static const float white[3] = {1, 1, 1}, grey[3] = {0.02f, 0.02f, 0.02f};
    const char *labels[3];
    mt_image maps[3], panels[3], out;
    double vmax[3] = {0, 0, 3};
    int k, c, ip, iz, w, h, pw, ph, cell = (168 + cfg->nphi - 1) / cfg->nphi;
    mt_status st = MT_OK;
    memset(maps, 0, sizeof maps);
    memset(panels, 0, sizeof panels);
    memset(&out, 0, sizeof out);
    labels[0] = expected_label;
    labels[1] = "samples";
    labels[2] = "|o - e| / sqrt(e)";
    for (k = 0; k < 3; ++k)
        if ((st = mt_image_create(&maps[k], cfg->nphi, cfg->nz, 1, err))) goto done;
    for (c = 0; c < cfg->nphi * cfg->nz; ++c) {
        double e = pdfc[c] * n, o = (double)counts[c], d = e > 0 ? (o - e) / sqrt(e) : (o > 0 ? 1e3 : 0);
        size_t at;
        ip = c / cfg->nz;
        iz = c % cfg->nz;
        at = (size_t)(cfg->nz - 1 - iz) * (size_t)cfg->nphi + (size_t)ip; /* cos theta = +1 at the top */
        maps[0].data[at] = (float)e;
        maps[1].data[at] = (float)o;
        maps[2].data[at] = (float)d;
        vmax[0] = fmax(vmax[0], e);
        vmax[1] = fmax(vmax[1], o);
        vmax[2] = fmax(vmax[2], fabs(d));
    }
    /* expected and observed on one scale, so that equal means equal colour */
    vmax[0] = vmax[1] = fmax(fmax(vmax[0], vmax[1]), 1);
    if (cell < 4) cell = 4; /* panels at least 168 pixels wide: room for the labels */
    pw = cfg->nphi * cell;
    ph = cfg->nz * cell;
    for (k = 0; k < 3; ++k)
        if ((st = mt_imgcmp_heatmap(&maps[k], cell, pw, ph, vmax[k], 1, &panels[k], err))) goto done;
    w = 3 * panels[0].width + 4 * GAP;
    if (mt__text_width(title, 1) + 2 * GAP > w) w = mt__text_width(title, 1) + 2 * GAP;
    if (mt__text_width(subtitle, 1) + 2 * GAP > w) w = mt__text_width(subtitle, 1) + 2 * GAP;
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
    mt__draw_text(&out, GAP, 3 * LINE + 4 + panels[0].height + 3,
                  "phi 0..2pi across, cos theta +1 (top) to -1 (bottom)", 1, white);
    st = mt_image_write(path, &out, NULL, 0, err);
done:
    for (k = 0; k < 3; ++k) {
        mt_image_destroy(&maps[k]);
        mt_image_destroy(&panels[k]);
    }
    mt_image_destroy(&out);
    return st ? -1 : 0;
}
