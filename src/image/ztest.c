/*
 * The z-test of a render against a golden mean and variance, per block and
 * channel, with the Sidak correction over all tests. Mitsuba 3's render
 * tests (src/render/tests/test_renders.py there) test per pixel with the
 * reference's per-sample variance (floored at 1e-4) divided by the test's
 * sample count, and accept when 99.75% of the pixels pass the Sidak
 * threshold; here both images' variances of the mean enter, blocks make the
 * means close to normal at low sample counts, and the smallest p-value
 * decides, so the false-alarm rate of an honest render is alpha; a global
 * test of the mean z per channel (half of alpha) adds the power to see a
 * small bias of the whole image that no single block shows.
 * Pixels are independent, so the variance of a block mean is the sum of its
 * pixels' variances of the mean divided by n^2.
 */
#include <float.h>
#include <math.h>
#include "core/alloc.h"
#include "image/cmpblocks.h"
#include "materia/tools/imgcmp.h"

mt_ztest_options mt_ztest_defaults(void)
{
    mt_ztest_options o;
    o.block = MT_IMGCMP_BLOCK;
    o.alpha = 0.01;
    o.exact_rel = 1e-4;
    return o;
}

/* Two-sided p-value of a standard normal z. */
static double p_two_sided(double z) { return erfc(fabs(z) / sqrt(2.0)); }

/* The |z| whose two-sided p-value is p (bisection: p_two_sided decreases;
 * erfc underflows past 38, far beyond any threshold of a real image). */
static double z_for_p(double p)
{
    double lo = 0, hi = 40;
    int i;
    for (i = 0; i < 200 && hi - lo > 1e-12; ++i) {
        double mid = 0.5 * (lo + hi);
        if (p_two_sided(mid) > p)
            lo = mid;
        else
            hi = mid;
    }
    return 0.5 * (lo + hi);
}

/* Block variances of the mean: the block mean of the pixel variances
 * divided by the block's pixel count (sum / n^2); zeros when var is NULL. */
static double *block_vars(const mt_image *var, const mt__grid *g, mt_error *err)
{
    size_t n = (size_t)g->bx * (size_t)g->by * (size_t)g->nc, k = 0;
    double *v;
    int i, j, c;
    if (!var) {
        v = mt__calloc(n, sizeof *v);
        if (!v) mt_error_set(err, MT_ERR_NOMEM, "out of memory for %lu block variances",
                             (unsigned long)n);
        return v;
    }
    if (!(v = mt__block_means(var, g, err))) return NULL;
    for (j = 0; j < g->by; ++j)
        for (i = 0; i < g->bx; ++i) {
            double np = mt__block_pixels(g, i, j);
            for (c = 0; c < g->nc; ++c, ++k) v[k] /= np;
        }
    return v;
}

/* Checks the options and the variance images. */
static mt_status check_inputs(const mt_image *var_a, const mt_image *var_b,
                              const mt_ztest_options *o, const mt__grid *g, mt_error *err)
{
    mt_status st;
    if (!(o->alpha > 0 && o->alpha < 1))
        return mt_error_param(err, MT_ERR_INVALID, "alpha",
                              "the significance must be between 0 and 1, not %g", o->alpha);
    if (!(o->exact_rel >= 0 && o->exact_rel < 1))
        return mt_error_param(err, MT_ERR_INVALID, "exact_rel",
                              "the tolerance of exact blocks must be in [0, 1), not %g",
                              o->exact_rel);
    if (var_a && (st = mt__cmp_check(var_a, "var_a", g, 1, err)) != MT_OK) return st;
    if (var_b && (st = mt__cmp_check(var_b, "var_b", g, 1, err)) != MT_OK) return st;
    return MT_OK;
}

/* A standard deviation below this fraction of the means is rounding, not
 * estimation noise: about 8 float epsilons, far above the ~1e-9 that float
 * accumulation leaves on identical samples, far below any Monte Carlo
 * noise a z-test is meant for. Kept apart from exact_rel (the tolerance of
 * the equality that replaces the z-test): with one number for both, a noisy
 * pair whose deviation is just below exact_rel would be asked for equality
 * within one standard deviation and fail about a third of the time. */
#define ROUNDING_SD 1e-6

/* Whether a pair is deterministic rather than noisy: no variance, or a
 * standard deviation of the difference at rounding level. A sky seen in a
 * mirror is the same value in every sample, but float accumulation leaves a
 * variance of ~1e-18 on a mean of 0.3 and the float and double builds' means
 * differ by ~1e-8: as a z-test that would be z = 70, a rounding difference
 * called a bias. */
static int pair_exact(double ma, double mb, double va, double vb)
{
    double s2 = va + vb, scale = fabs(ma) > fabs(mb) ? fabs(ma) : fabs(mb);
    return !(s2 > 0) || s2 <= ROUNDING_SD * scale * ROUNDING_SD * scale;
}

/* The z of one block-channel pair, or for an exact pair 0 when the means
 * agree within exact_rel and +-FLT_MAX when they do not; *exact says which. */
static double pair_z(double ma, double mb, double va, double vb, double exact_rel, int *exact)
{
    double scale = fabs(ma) > fabs(mb) ? fabs(ma) : fabs(mb);
    *exact = pair_exact(ma, mb, va, vb);
    if (!*exact) return (ma - mb) / sqrt(va + vb);
    if (fabs(ma - mb) <= exact_rel * scale) return 0;
    return ma > mb ? FLT_MAX : -FLT_MAX;
}

mt_status mt_imgcmp_ztest(const mt_image *a, const mt_image *var_a, const mt_image *b,
                          const mt_image *var_b, const mt_ztest_options *opt,
                          mt_ztest_result *out, mt_image *zmap, mt_error *err)
{
    mt_ztest_options o = opt ? *opt : mt_ztest_defaults();
    mt__grid g;
    mt_status st;
    double *ma = NULL, *mb = NULL, *va = NULL, *vb = NULL, rel = 0, min_p = 1;
    double zsum[3] = {0, 0, 0};
    long zcount[3] = {0, 0, 0};
    size_t n, k;
    int c;
    mt_error_clear(err);
    if (!out) return mt_error_set(err, MT_ERR_INVALID, "mt_imgcmp_ztest: no output");
    if ((st = mt__cmp_pair(a, b, o.block, &g, err)) != MT_OK) return st;
    if ((st = check_inputs(var_a, var_b, &o, &g, err)) != MT_OK) return st;
    if (!(ma = mt__block_means(a, &g, err)) || !(mb = mt__block_means(b, &g, err)) ||
        !(va = block_vars(var_a, &g, err)) || !(vb = block_vars(var_b, &g, err))) {
        st = MT_ERR_NOMEM;
        goto done;
    }
    n = (size_t)g.bx * (size_t)g.by * (size_t)g.nc;
    out->tests = out->exact = out->exact_mismatch = out->beyond = 0;
    for (k = 0; k < n; ++k) out->tests += !pair_exact(ma[k], mb[k], va[k], vb[k]);
    /* 1 - (1 - alpha/2)^(1/m) without cancellation for large m; the other
     * half of alpha goes to the channels' global tests */
    out->threshold = out->tests ? -expm1(log1p(-0.5 * o.alpha) / (double)out->tests) : o.alpha;
    out->z_threshold = z_for_p(out->threshold);
    out->bias_z_threshold = z_for_p(-expm1(log1p(-0.5 * o.alpha) / (double)g.nc));
    out->max_abs_z = 0;
    out->max_bx = out->max_by = out->max_c = -1;
    for (k = 0; k < n; ++k) {
        int exact;
        double z = pair_z(ma[k], mb[k], va[k], vb[k], o.exact_rel, &exact);
        rel += mt__reldiff(ma[k], mb[k]);
        if (exact) {
            out->exact++;
            out->exact_mismatch += z != 0;
        } else {
            double p = p_two_sided(z);
            if (p < min_p) min_p = p;
            zsum[k % (size_t)g.nc] += z;
            zcount[k % (size_t)g.nc]++;
            out->beyond += p <= out->threshold;
            if (fabs(z) > out->max_abs_z || out->max_bx < 0) {
                size_t blk = k / (size_t)g.nc;
                out->max_abs_z = fabs(z);
                out->max_bx = (int)(blk % (size_t)g.bx);
                out->max_by = (int)(blk / (size_t)g.bx);
                out->max_c = (int)(k % (size_t)g.nc);
            }
        }
        va[k] = z; /* the z map, in place */
    }
    out->min_p = min_p;
    out->mean_rel = rel / (double)n;
    out->pass = out->exact_mismatch == 0 && min_p > out->threshold;
    out->bias_c = -1;
    for (c = 0; c < 3; ++c) {
        out->bias_z[c] = zcount[c] ? zsum[c] / sqrt((double)zcount[c]) : 0;
        if (c < g.nc && zcount[c] && (out->bias_c < 0 || fabs(out->bias_z[c]) > fabs(out->bias_z[out->bias_c])))
            out->bias_c = c;
    }
    if (out->bias_c >= 0 && !(fabs(out->bias_z[out->bias_c]) < out->bias_z_threshold)) out->pass = 0;
    out->blocks_x = g.bx;
    out->blocks_y = g.by;
    out->channels = g.nc;
    st = zmap ? mt__blocks_image(va, &g, zmap, err) : MT_OK;
done:
    mt__free(ma);
    mt__free(mb);
    mt__free(va);
    mt__free(vb);
    return st;
}
