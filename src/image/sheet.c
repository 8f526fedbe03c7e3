/*
 * Contact sheets: a grid of tone-mapped images with labels.
 */
#include <math.h>
#include <string.h>
#include "image/font.h"
#include "materia/tools/sheet.h"

/* Linear grey of the background: about 10% on screen after sRGB. */
#define SHEET_BACKGROUND 0.01f

mt_sheet_options mt_sheet_defaults(void)
{
    mt_sheet_options o;
    o.columns = 0;
    o.font_scale = 1;
    o.exposure = 0;
    o.gap = 4;
    return o;
}

static mt_status check(const mt_sheet_entry *e, int n, const mt_sheet_options *o, mt_error *err)
{
    int i;
    if (!e || n < 1) return mt_error_set(err, MT_ERR_INVALID, "a contact sheet needs images");
    for (i = 0; i < n; ++i)
        if (!e[i].image || !e[i].image->data || e[i].image->width < 1 ||
            e[i].image->height < 1)
            return mt_error_set(err, MT_ERR_INVALID, "contact sheet entry %d (%s) has no image",
                                i, e[i].label ? e[i].label : "unlabelled");
    if (o->columns < 0 || o->columns > 4096)
        return mt_error_param(err, MT_ERR_INVALID, "columns", "%d columns", o->columns);
    if (o->font_scale < 1 || o->font_scale > 16)
        return mt_error_param(err, MT_ERR_INVALID, "font_scale",
                              "the font scale is between 1 and 16, not %d", o->font_scale);
    if (o->gap < 0 || o->gap > 1024)
        return mt_error_param(err, MT_ERR_INVALID, "gap", "a gap of %d pixels", o->gap);
    if (!isfinite(o->exposure) || fabs(o->exposure) > 64)
        return mt_error_param(err, MT_ERR_INVALID, "exposure",
                              "the exposure is between -64 and 64 stops, not %g", o->exposure);
    return MT_OK;
}

/* Copies img, tone mapped, with its top-left corner at (x0, y0). */
static void place(mt_image *out, const mt_image *img, int x0, int y0, float scale)
{
    int x, y, c;
    for (y = 0; y < img->height; ++y)
        for (x = 0; x < img->width; ++x) {
            const float *s = img->data + ((size_t)y * (size_t)img->width + (size_t)x) *
                                             (size_t)img->channels;
            float *d = out->data + ((size_t)(y0 + y) * (size_t)out->width + (size_t)(x0 + x)) * 3;
            int bad = 0;
            for (c = 0; c < 3; ++c) {
                float v = s[img->channels == 1 ? 0 : c] * scale;
                bad |= !isfinite(v);
                d[c] = v > 1 ? 1 : (v > 0 ? v : 0);
            }
            if (bad) {
                d[0] = d[2] = 1;
                d[1] = 0;
            }
        }
}

/* Draws label centred under a cell of width cw at (x0, y), cut to fit. */
static void label(mt_image *out, const char *text, int x0, int y, int cw, int scale)
{
    static const float white[3] = {1, 1, 1};
    char buf[256];
    size_t n = strlen(text);
    if (n >= sizeof buf) n = sizeof buf - 1;
    memcpy(buf, text, n);
    buf[n] = 0;
    while (n > 0 && mt__text_width(buf, scale) > cw) buf[--n] = 0;
    mt__draw_text(out, x0 + (cw - mt__text_width(buf, scale)) / 2, y, buf, scale, white);
}

mt_status mt_sheet_make(const mt_sheet_entry *entries, int n, const mt_sheet_options *opt,
                        mt_image *out, mt_error *err)
{
    mt_sheet_options o = opt ? *opt : mt_sheet_defaults();
    int cols, rows, cw = 0, ch = 0, lh, i, w, h;
    long long ws, hs;
    size_t k;
    mt_status st;
    float scale;
    mt_error_clear(err);
    if (!out) return mt_error_set(err, MT_ERR_INVALID, "mt_sheet_make: no output");
    if ((st = check(entries, n, &o, err)) != MT_OK) return st;
    cols = o.columns;
    if (cols == 0)
        for (cols = 1; (long long)cols * cols < n;) ++cols;
    if (cols > n) cols = n;
    rows = (n + cols - 1) / cols;
    for (i = 0; i < n; ++i) {
        if (entries[i].image->width > cw) cw = entries[i].image->width;
        if (entries[i].image->height > ch) ch = entries[i].image->height;
    }
    lh = o.gap + MT__FONT_H * o.font_scale;
    ws = (long long)cols * cw + (long long)(cols + 1) * o.gap;
    hs = (long long)rows * (ch + lh) + (long long)(rows + 1) * o.gap;
    if (ws > 65536 || hs > 65536)
        return mt_error_set(err, MT_ERR_INVALID, "a contact sheet of %lld x %lld pixels is too large",
                            ws, hs);
    w = (int)ws;
    h = (int)hs;
    if ((st = mt_image_create(out, w, h, 3, err)) != MT_OK) return st;
    for (k = 0; k < (size_t)w * (size_t)h * 3; ++k) out->data[k] = SHEET_BACKGROUND;
    scale = (float)pow(2.0, o.exposure);
    for (i = 0; i < n; ++i) {
        const mt_image *img = entries[i].image;
        int x0 = o.gap + (i % cols) * (cw + o.gap), y0 = o.gap + (i / cols) * (ch + lh + o.gap);
        place(out, img, x0 + (cw - img->width) / 2, y0, scale);
        if (entries[i].label) label(out, entries[i].label, x0, y0 + ch + o.gap, cw, o.font_scale);
    }
    return MT_OK;
}
