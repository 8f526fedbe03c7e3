/*
 * pbrt-v2's ImageFilm: crop window (ImageFilm constructor), sample extent
 * (GetSampleExtent), AddSample's pixel range, WriteImage's normalization.
 */
#include <math.h>
#include <string.h>
#include "core/alloc.h"
#include "tracer/film.h"

/* floor and ceil to int without libm calls (x86-64's baseline has no
 * rounding instruction, so floor() is a call); |v| < 2^31 here. */
static int floor_int(double v)
{
    int i = (int)v;
    return (double)i > v ? i - 1 : i;
}
static int ceil_int(double v)
{
    int i = (int)v;
    return (double)i < v ? i + 1 : i;
}

void mt__film_init(mt__film *f, int xres, int yres, const mt_real crop_in[4],
                   const mt__filter *filter)
{
    double c[4], xw = filter->xwidth, yw = filter->ywidth;
    int i;
    c[0] = mt_min(crop_in[0], crop_in[1]);
    c[1] = mt_max(crop_in[0], crop_in[1]);
    c[2] = mt_min(crop_in[2], crop_in[3]);
    c[3] = mt_max(crop_in[2], crop_in[3]);
    for (i = 0; i < 4; ++i) c[i] = c[i] < 0 ? 0 : (c[i] > 1 ? 1 : c[i]);
    f->xres = xres;
    f->yres = yres;
    f->filter = *filter;
    /* pbrt-v2: xPixelStart = Ceil2Int(xres * crop[0]), xPixelCount =
     * max(1, Ceil2Int(xres * crop[1]) - xPixelStart) (in float) */
    f->x0 = ceil_int((float)xres * (float)c[0]);
    f->width = ceil_int((float)xres * (float)c[1]) - f->x0;
    if (f->width < 1) f->width = 1;
    f->y0 = ceil_int((float)yres * (float)c[2]);
    f->height = ceil_int((float)yres * (float)c[3]) - f->y0;
    if (f->height < 1) f->height = 1;
    /* Samples at ix reach pixels up to floor(ix - 0.5 + xw) and down to
     * ceil(ix - 0.5 - xw). pbrt-v2's extent, floor(x0 + 0.5 - xw) to
     * floor(x1 + 0.5 + xw) exclusive, adds a column and a row that only
     * reach the image at single points (ix exactly x1 - 0.5 + xw); they are
     * left out here (a set of measure zero). */
    f->sx0 = floor_int(f->x0 + 0.5 - xw);
    f->sx1 = ceil_int(f->x0 + f->width - 0.5 + xw);
    f->sy0 = floor_int(f->y0 + 0.5 - yw);
    f->sy1 = ceil_int(f->y0 + f->height - 0.5 + yw);
}

/* The pixel range [*lo, *hi) that samples in [s0, s1) reach along one axis,
 * within [p0, p0 + n). */
static void reach(int s0, int s1, double w, int p0, int n, int *lo, int *hi)
{
    int a = ceil_int(s0 - 0.5 - w), b = floor_int(s1 - 0.5 + w) + 1;
    if (a < p0) a = p0;
    if (b > p0 + n) b = p0 + n;
    if (b < a) b = a;
    *lo = a;
    *hi = b;
}

size_t mt__film_tile_pixels(const mt__film *f, int tile)
{
    size_t w = (size_t)tile + 2 * (size_t)ceil(f->filter.xwidth) + 2;
    size_t h = (size_t)tile + 2 * (size_t)ceil(f->filter.ywidth) + 2;
    return w * h;
}

void mt__film_buf_cover(const mt__film *f, mt__film_buf *b, int sx0, int sx1, int sy0, int sy1)
{
    int x1, y1;
    reach(sx0, sx1, f->filter.xwidth, f->x0, f->width, &b->x0, &x1);
    reach(sy0, sy1, f->filter.ywidth, f->y0, f->height, &b->y0, &y1);
    b->w = x1 - b->x0;
    b->h = y1 - b->y0;
    if ((size_t)b->w * (size_t)b->h > b->cap) b->w = b->h = 0; /* never: cap from tile_pixels */
    memset(b->px, 0, (size_t)b->w * (size_t)b->h * sizeof *b->px);
}

mt_status mt__film_buf_alloc(mt__film_buf *b, size_t pixels, mt_error *err)
{
    memset(b, 0, sizeof *b);
    b->px = mt__calloc(pixels ? pixels : 1, sizeof *b->px);
    if (!b->px)
        return mt_error_set(err, MT_ERR_NOMEM, "out of memory for a film buffer of %lu pixels",
                            (unsigned long)pixels);
    b->cap = pixels;
    b->second_moments = 1;
    return MT_OK;
}

void mt__film_buf_free(mt__film_buf *b)
{
    mt__free(b->px);
    b->px = NULL;
    b->cap = 0;
}

static void accumulate(mt__pixel_acc *a, double w, const double l[3], int second_moments)
{
    double w2 = w * w;
    int c;
    a->w += w;
    for (c = 0; c < 3; ++c) a->wl[c] += w * l[c];
    if (!second_moments) return;
    a->w2 += w2;
    for (c = 0; c < 3; ++c) {
        a->w2l[c] += w2 * l[c];
        a->w2l2[c] += w2 * l[c] * l[c];
    }
}

void mt__film_add(const mt__film *f, mt__film_buf *b, mt_real ix, mt_real iy, mt_rgb L)
{
    const mt__filter *flt = &f->filter;
    double dx = (double)ix - 0.5, dy = (double)iy - 0.5, l[3];
    int x0 = ceil_int(dx - flt->xwidth), x1 = floor_int(dx + flt->xwidth);
    int y0 = ceil_int(dy - flt->ywidth), y1 = floor_int(dy + flt->ywidth), x, y;
    l[0] = L.c[0];
    l[1] = L.c[1];
    l[2] = L.c[2];
    if (x0 == x1 && y0 == y1 && flt->kind == MT__FILTER_BOX) {
        /* pbrt-v2's default: a box of half-width 0.5 reaches one pixel */
        if (x0 >= b->x0 && x0 < b->x0 + b->w && y0 >= b->y0 && y0 < b->y0 + b->h)
            accumulate(&b->px[(size_t)(y0 - b->y0) * (size_t)b->w + (size_t)(x0 - b->x0)], 1.0, l,
                       b->second_moments);
        return;
    }
    if (x0 < b->x0) x0 = b->x0;
    if (x1 > b->x0 + b->w - 1) x1 = b->x0 + b->w - 1;
    if (y0 < b->y0) y0 = b->y0;
    if (y1 > b->y0 + b->h - 1) y1 = b->y0 + b->h - 1;
    for (y = y0; y <= y1; ++y) {
        mt__pixel_acc *row = b->px + (size_t)(y - b->y0) * (size_t)b->w - b->x0;
        for (x = x0; x <= x1; ++x) {
            double w = flt->kind == MT__FILTER_BOX
                           ? 1.0
                           : (double)mt__filter_eval(flt, (mt_real)(x - dx), (mt_real)(y - dy));
            accumulate(&row[x], w, l, b->second_moments);
        }
    }
}

void mt__film_buf_merge(mt__film_buf *dst, const mt__film_buf *src)
{
    int x, y, c;
    for (y = 0; y < src->h; ++y) {
        const mt__pixel_acc *s = src->px + (size_t)y * (size_t)src->w;
        mt__pixel_acc *d = dst->px + (size_t)(y + src->y0 - dst->y0) * (size_t)dst->w +
                           (src->x0 - dst->x0);
        for (x = 0; x < src->w; ++x) {
            d[x].w += s[x].w;
            d[x].w2 += s[x].w2;
            for (c = 0; c < 3; ++c) {
                d[x].wl[c] += s[x].wl[c];
                d[x].w2l[c] += s[x].w2l[c];
                d[x].w2l2[c] += s[x].w2l2[c];
            }
        }
    }
}

mt_status mt__film_develop(const mt__film *f, const mt__film_buf *b, mt_image *img,
                           mt_image *var, mt_error *err)
{
    size_t i, n = (size_t)f->width * (size_t)f->height;
    int c;
    mt_status st = mt_image_create(img, f->width, f->height, 3, err);
    if (st != MT_OK) return st;
    if (var && (st = mt_image_create(var, f->width, f->height, 3, err)) != MT_OK) {
        mt_image_destroy(img);
        return st;
    }
    for (i = 0; i < n; ++i) {
        const mt__pixel_acc *a = &b->px[i];
        double neff = a->w2 > 0 ? a->w * a->w / a->w2 : 0;
        for (c = 0; c < 3; ++c) {
            double m = a->w != 0 ? a->wl[c] / a->w : 0, v = 0;
            img->data[3 * i + c] = (float)(m > 0 ? m : 0);
            if (!var) continue;
            if (neff > 1 + 1e-9) {
                /* sum w^2 (L - m)^2 = sum w^2 L^2 - 2 m sum w^2 L + m^2 sum w^2 */
                double ss = a->w2l2[c] - 2 * m * a->w2l[c] + m * m * a->w2;
                v = ss > 0 ? ss / (a->w * a->w) * neff / (neff - 1) : 0;
            }
            var->data[3 * i + c] = (float)v;
        }
    }
    return MT_OK;
}
