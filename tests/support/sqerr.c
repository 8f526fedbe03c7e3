/* The squared error against a noisy reference, its noise subtracted (sqerr.h). */
#include <math.h>
#include <stdio.h>
#include "materia/tools/imgcmp.h"
#include "support/sqerr.h"

static int colour_channels(const mt_image *img)
{
    return img->channels >= 3 ? 3 : 1;
}

static int same_shape(const mt_image *x, const mt_image *ref, const char *what, char *msg, size_t msglen)
{
    if (!x->data || x->width != ref->width || x->height != ref->height ||
        colour_channels(x) != colour_channels(ref)) {
        snprintf(msg, msglen, "%s is %dx%d with %d channels, the reference %dx%d with %d", what, x->width,
                 x->height, x->channels, ref->width, ref->height, ref->channels);
        return 0;
    }
    return 1;
}

static double at(const mt_image *img, size_t pixel, int c)
{
    return img->data[pixel * (size_t)img->channels + (size_t)c];
}

int t_sqerr_compute(const mt_image *a, const mt_image *va, const mt_image *b, const mt_image *vb,
                    t_sqerr *out, char *msg, size_t msglen)
{
    size_t p, npix;
    int c, nc;
    double se = 0, rse = 0, sv = 0, rsv = 0, sva = 0;
    if (!b->data || !same_shape(a, b, "the image", msg, msglen) ||
        (vb && !same_shape(vb, b, "the reference's variance", msg, msglen)) ||
        (va && !same_shape(va, b, "the image's variance", msg, msglen)))
        return -1;
    nc = colour_channels(b);
    npix = (size_t)b->width * (size_t)b->height;
    for (p = 0; p < npix; ++p)
        for (c = 0; c < nc; ++c) {
            double x = at(a, p, c), y = at(b, p, c), v = vb ? at(vb, p, c) : 0, w = 1 / (y * y + MT_IMGCMP_OFFSET);
            double d = x - y;
            if (!(v >= 0) || isinf(v) || (va && (!(at(va, p, c) >= 0) || isinf(at(va, p, c))))) {
                snprintf(msg, msglen, "pixel (%d, %d) channel %d: variance %g (must be finite, not negative)",
                         (int)(p % (size_t)b->width), (int)(p / (size_t)b->width), c,
                         !(v >= 0) || isinf(v) ? v : at(va, p, c));
                return -1;
            }
            se += d * d;
            rse += d * d * w;
            sv += v;
            rsv += v * w;
            if (va) sva += at(va, p, c);
        }
    out->n = npix * (size_t)nc;
    out->mse_raw = se / (double)out->n;
    out->ref_var = sv / (double)out->n;
    out->mse = out->mse_raw - out->ref_var;
    out->relmse_raw = rse / (double)out->n;
    out->relmse = (rse - rsv) / (double)out->n;
    out->a_var = va ? sva / (double)out->n : -1;
    return 0;
}

int t_sqerr_pair(const mt_image *r1, const mt_image *r2, mt_image *mean, mt_image *var, char *msg,
                 size_t msglen)
{
    mt_error err;
    mt_imgacc *acc;
    mt_status st = MT_OK;
    if (!r1->data || !same_shape(r2, r1, "the second render", msg, msglen)) return -1;
    acc = mt_imgacc_create(r1->width, r1->height, r1->channels, &err);
    if (acc) {
        st = mt_imgacc_add_image(acc, r1, &err);
        if (st == MT_OK) st = mt_imgacc_add_image(acc, r2, &err);
        if (st == MT_OK) st = mt_imgacc_finish(acc, mean, var, &err);
        mt_imgacc_destroy(acc);
    }
    if (!acc || st != MT_OK) {
        mt_error_format(&err, msg, msglen);
        return -1;
    }
    return 0;
}
