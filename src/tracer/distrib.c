/*
 * pbrt-v2's Distribution1D and Distribution2D (core/montecarlo.h/.cpp):
 * cdf[i] = cdf[i-1] + func[i-1] / n normalized by funcInt = cdf[n] (uniform
 * steps when funcInt is 0); sampling finds the segment with upper_bound and
 * inverts linearly within it.
 */
#include "core/alloc.h"
#include "tracer/distrib.h"

mt_status mt__distrib1d_init(mt__distrib1d *d, const mt_real *f, int count, mt_error *err)
{
    int i;
    d->count = count;
    d->func = mt__malloc((size_t)count * sizeof *d->func);
    d->cdf = mt__malloc(((size_t)count + 1) * sizeof *d->cdf);
    if (!d->func || !d->cdf) {
        mt__distrib1d_free(d);
        return mt_error_set(err, MT_ERR_NOMEM, "out of memory for a distribution of %d values",
                            count);
    }
    for (i = 0; i < count; ++i) d->func[i] = f[i];
    d->cdf[0] = 0;
    for (i = 1; i <= count; ++i) d->cdf[i] = d->cdf[i - 1] + d->func[i - 1] / (mt_real)count;
    d->func_int = d->cdf[count];
    for (i = 1; i <= count; ++i)
        d->cdf[i] = d->func_int == 0 ? (mt_real)i / (mt_real)count : d->cdf[i] / d->func_int;
    return MT_OK;
}

void mt__distrib1d_free(mt__distrib1d *d)
{
    mt__free(d->func);
    mt__free(d->cdf);
    d->func = d->cdf = NULL;
}

mt_real mt__distrib1d_sample(const mt__distrib1d *d, mt_real u, mt_real *pdf, int *offset)
{
    /* the first cdf entry above u (std::upper_bound), then one back */
    int lo = 0, hi = d->count + 1, i;
    mt_real du, width;
    /* one value (a constant infinite light): the search's answer, lo = 1
     * for any u < cdf[1] = 1, without the search */
    if (d->count == 1 && u < d->cdf[1]) lo = hi = 1;
    while (lo < hi) {
        int mid = lo + (hi - lo) / 2;
        if (d->cdf[mid] > u) hi = mid;
        else lo = mid + 1;
    }
    i = lo - 1;
    if (i < 0) i = 0;
    if (i > d->count - 1) i = d->count - 1;
    if (offset) *offset = i;
    width = d->cdf[i + 1] - d->cdf[i];
    du = width > 0 ? (u - d->cdf[i]) / width : 0;
    if (pdf) *pdf = d->func_int > 0 ? d->func[i] / d->func_int : 0;
    return ((mt_real)i + du) / (mt_real)d->count;
}

mt_status mt__distrib2d_init(mt__distrib2d *d, const mt_real *func, int nu, int nv, mt_error *err)
{
    mt_real *marg;
    mt_status st = MT_OK;
    int v;
    d->nu = nu;
    d->nv = nv;
    d->marginal.func = d->marginal.cdf = NULL;
    d->conditional = mt__calloc((size_t)nv, sizeof *d->conditional);
    marg = mt__malloc((size_t)nv * sizeof *marg);
    if (!d->conditional || !marg) {
        mt__free(marg);
        mt__free(d->conditional);
        d->conditional = NULL;
        return mt_error_set(err, MT_ERR_NOMEM, "out of memory for a %dx%d distribution", nu, nv);
    }
    for (v = 0; v < nv && st == MT_OK; ++v) {
        st = mt__distrib1d_init(&d->conditional[v], func + (size_t)v * (size_t)nu, nu, err);
        if (st == MT_OK) marg[v] = d->conditional[v].func_int;
    }
    if (st == MT_OK) st = mt__distrib1d_init(&d->marginal, marg, nv, err);
    mt__free(marg);
    if (st != MT_OK) mt__distrib2d_free(d);
    return st;
}

void mt__distrib2d_free(mt__distrib2d *d)
{
    int v;
    if (d->conditional)
        for (v = 0; v < d->nv; ++v) mt__distrib1d_free(&d->conditional[v]);
    mt__free(d->conditional);
    d->conditional = NULL;
    mt__distrib1d_free(&d->marginal);
}

void mt__distrib2d_sample(const mt__distrib2d *d, mt_real u0, mt_real u1, mt_real uv[2],
                          mt_real *pdf)
{
    mt_real p0, p1;
    int v;
    uv[1] = mt__distrib1d_sample(&d->marginal, u1, &p1, &v);
    uv[0] = mt__distrib1d_sample(&d->conditional[v], u0, &p0, NULL);
    *pdf = p0 * p1;
}

mt_real mt__distrib2d_pdf(const mt__distrib2d *d, mt_real u, mt_real v)
{
    /* pbrt-v2: Clamp(Float2Int(u * count), 0, count - 1) */
    mt_real fu = u * (mt_real)d->nu, fv = v * (mt_real)d->nv;
    int iu = fu >= (mt_real)d->nu ? d->nu - 1 : (fu > 0 ? (int)fu : 0);
    int iv = fv >= (mt_real)d->nv ? d->nv - 1 : (fv > 0 ? (int)fv : 0);
    mt_real denom = d->conditional[iv].func_int * d->marginal.func_int;
    if (!(denom > 0)) return 0;
    return d->conditional[iv].func[iu] * d->marginal.func[iv] / denom;
}
