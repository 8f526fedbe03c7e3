/*
 * pbrt-v2's pixel filters: box.cpp, gaussian.h/.cpp, mitchell.h/.cpp,
 * triangle.cpp, sinc.h/.cpp -- their formulas and defaults.
 */
#include <string.h>
#include "tracer/filter.h"

static mt_real gaussian1d(const mt__filter *f, mt_real d, mt_real expv)
{
    return mt_max(0, mt_exp(-f->alpha * d * d) - expv);
}

static mt_real mitchell1d(const mt__filter *f, mt_real x)
{
    mt_real B = f->B, C = f->C;
    x = mt_fabs(2 * x);
    if (x > 1)
        return ((-B - 6 * C) * x * x * x + (6 * B + 30 * C) * x * x + (-12 * B - 48 * C) * x +
                (8 * B + 24 * C)) *
               ((mt_real)1 / 6);
    return ((12 - 9 * B - 6 * C) * x * x * x + (-18 + 12 * B + 6 * C) * x * x + (6 - 2 * B)) *
           ((mt_real)1 / 6);
}

/* pbrt-v2's LanczosSincFilter::Sinc1D, argument already divided by the width. */
static mt_real sinc1d(const mt__filter *f, mt_real x)
{
    mt_real sinc, lanczos;
    x = mt_fabs(x);
    if (x < (mt_real)1e-5) return 1;
    if (x > 1) return 0;
    x *= MT_PI;
    sinc = mt_sin(x) / x;
    lanczos = mt_sin(x * f->tau) / (x * f->tau);
    return sinc * lanczos;
}

mt_real mt__filter_eval(const mt__filter *f, mt_real x, mt_real y)
{
    switch (f->kind) {
    case MT__FILTER_BOX: return 1;
    case MT__FILTER_GAUSSIAN: return gaussian1d(f, x, f->exp_x) * gaussian1d(f, y, f->exp_y);
    case MT__FILTER_MITCHELL:
        return mitchell1d(f, x * f->inv_xwidth) * mitchell1d(f, y * f->inv_ywidth);
    case MT__FILTER_TRIANGLE:
        return mt_max(0, f->xwidth - mt_fabs(x)) * mt_max(0, f->ywidth - mt_fabs(y));
    case MT__FILTER_SINC: return sinc1d(f, x * f->inv_xwidth) * sinc1d(f, y * f->inv_ywidth);
    }
    return 0;
}

static const struct {
    const char *name;
    mt__filter_kind kind;
    mt_real width;
} kinds[] = {{"box", MT__FILTER_BOX, (mt_real)0.5},
             {"gaussian", MT__FILTER_GAUSSIAN, 2},
             {"mitchell", MT__FILTER_MITCHELL, 2},
             {"triangle", MT__FILTER_TRIANGLE, 2},
             {"sinc", MT__FILTER_SINC, 4}};

mt_status mt__filter_create(mt__filter *f, const char *name, const mt_paramset *ps, mt_error *err)
{
    size_t i;
    mt_status st;
    memset(f, 0, sizeof *f);
    for (i = 0; i < sizeof kinds / sizeof kinds[0]; ++i)
        if (strcmp(kinds[i].name, name) == 0) break;
    if (i == sizeof kinds / sizeof kinds[0])
        return mt_error_set(err, MT_ERR_NOT_FOUND,
                            "PixelFilter \"%s\" unknown (box, gaussian, mitchell, triangle, sinc)",
                            name);
    f->kind = kinds[i].kind;
    if ((st = mt_params_float(ps, "xwidth", kinds[i].width, &f->xwidth, err)) != MT_OK ||
        (st = mt_params_float(ps, "ywidth", kinds[i].width, &f->ywidth, err)) != MT_OK)
        return st;
    if (!(f->xwidth > 0) || !(f->ywidth > 0) || f->xwidth > 64 || f->ywidth > 64)
        return mt_error_param(err, MT_ERR_INVALID, f->xwidth > 0 && f->xwidth <= 64 ? "ywidth" : "xwidth",
                              "PixelFilter \"%s\": the widths must be in (0, 64]", name);
    f->inv_xwidth = 1 / f->xwidth;
    f->inv_ywidth = 1 / f->ywidth;
    switch (f->kind) {
    case MT__FILTER_GAUSSIAN:
        if ((st = mt_params_float(ps, "alpha", 2, &f->alpha, err)) != MT_OK) return st;
        f->exp_x = mt_exp(-f->alpha * f->xwidth * f->xwidth);
        f->exp_y = mt_exp(-f->alpha * f->ywidth * f->ywidth);
        break;
    case MT__FILTER_MITCHELL:
        if ((st = mt_params_float(ps, "B", (mt_real)1 / 3, &f->B, err)) != MT_OK ||
            (st = mt_params_float(ps, "C", (mt_real)1 / 3, &f->C, err)) != MT_OK)
            return st;
        break;
    case MT__FILTER_SINC:
        if ((st = mt_params_float(ps, "tau", 3, &f->tau, err)) != MT_OK) return st;
        if (f->tau == 0) /* sin(0) / 0 */
            return mt_error_param(err, MT_ERR_INVALID, "tau", "PixelFilter \"sinc\": tau must not be 0");
        break;
    default: break;
    }
    return MT_OK;
}
