/*
 * The sampling checks, from one pass of samples per incoming direction:
 *
 *  identity   every sample's pdf equals Pdf(wo, wi) and its f equals f(wo, wi)
 *             (non-specular components), wi is a unit vector, f >= 0, pdf > 0,
 *             nothing is NaN or infinite;
 *  chi2       the sampled directions follow Pdf(): the whole sphere in
 *             equal-area cells (phi x cos theta, an odd number of rows so the
 *             horizon is inside a row), expected counts by adaptive cubature
 *             of Pdf() in double, cells below 5 expected pooled, a sample in a
 *             cell whose expected count is 0 a hard failure, the failed
 *             samples one more cell; significance with the Sidak correction
 *             over the whole suite;
 *  integral   the pdf's integral over the sphere equals the fraction of
 *             samples that succeed;
 *  furnace    rho(wo) by quadrature (the same cubature of f |cos|, plus the
 *             delta lobes' weights) agrees with the Monte Carlo estimate from
 *             the BSDF's own sampler, and meets the catalog's expectation.
 */
#include <float.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "conformance.h"
#include "support/check.h"

#define TWO_PI 6.283185307179586476925
#define MAXWO 8

#if MT_USE_DOUBLE
#define EPS DBL_EPSILON
#define IDENTITY_TOL 1e-5
#else
#define EPS FLT_EPSILON
#define IDENTITY_TOL 1e-3
#endif

/* Rounding noise of the float formulas: a lobe cos^e amplifies the relative
 * error of the cosine e times (pbrt-v2's own noise, not an error to find). */
static double noise_allowance(const cf_subject *s)
{
    double e = s->lobe_exponent > 1 ? s->lobe_exponent : 1;
    return 3 * e * EPS + 64 * EPS;
}

typedef cf_bsdf_pass pass;

void cf_bsdf_integrand(void *ctx, double phi, double z, double *out)
{
    const pass *p = ctx;
    mt_vec3 wi = mt_sphere_direction(phi, z);
    mt_rgb f = mt_bsdf_f(p->bsdf, p->wo, wi, p->flags);
    double c = fabs(z), pdf = mt_bsdf_pdf(p->bsdf, p->wo, wi, p->flags);
    out[0] = pdf;
    out[1] = f.c[0] * c;
    out[2] = f.c[1] * c;
    out[3] = f.c[2] * c;
    /* energy no sample can reach: f > 0 where the pdf is 0 (a shading
     * normal tilted from the geometric one leaves such a region) */
    out[4] = pdf > 0 ? 0 : out[1];
    out[5] = pdf > 0 ? 0 : out[2];
    out[6] = pdf > 0 ? 0 : out[3];
}

int cf_cell_of(const cf_config *cfg, mt_vec3 w)
{
    double phi = atan2(w.y, w.x), z = w.z;
    int ip, iz;
    if (phi < 0) phi += TWO_PI;
    ip = (int)(phi / TWO_PI * cfg->nphi);
    iz = (int)((z + 1) / 2 * cfg->nz);
    if (ip >= cfg->nphi) ip = cfg->nphi - 1;
    if (ip < 0) ip = 0;
    if (iz >= cfg->nz) iz = cfg->nz - 1;
    if (iz < 0) iz = 0;
    return ip * cfg->nz + iz;
}

/* Integrates the integrand's 7 components (pdf, f |cos| and the part of it
 * where the pdf is 0) over cell c. A cell that received many more samples
 * than the average holds a peak, and starts from a finer grid (see
 * mt_cubature_grid for why). */
mt_status cf_integrate_cell(mt_cubature_fn f, void *ctx, const cf_config *cfg, int c, long count, long n,
                            double abs_tol, double out[7], double *err_pdf, mt_error *err)
{
    int ncell = cfg->nphi * cfg->nz, ip = c / cfg->nz, iz = c % cfg->nz, part, k;
    int sub = mt_cubature_grid((double)count * ncell / (double)n);
    double p0 = TWO_PI * ip / cfg->nphi, p1 = TWO_PI * (ip + 1) / cfg->nphi;
    double z0 = -1 + 2.0 * iz / cfg->nz, z1 = -1 + 2.0 * (iz + 1) / cfg->nz;
    for (k = 0; k < 7; ++k) out[k] = 0;
    *err_pdf = 0;
    /* the horizon splits the middle row: integrate its halves apart */
    for (part = 0; part < 2; ++part) {
        double a = z0, b = z1;
        mt_cubature_result r;
        mt_status st;
        if (z0 < 0 && z1 > 0) {
            if (part == 0)
                b = 0;
            else
                a = 0;
        } else if (part == 1) {
            break;
        }
        st = mt_cubature(f, ctx, 7, p0, p1, a, b, sub, sub, 1e-7, abs_tol, 225L * 8 * sub * sub, &r, err);
        if (st) return st;
        for (k = 0; k < 7; ++k) out[k] += r.value[k];
        *err_pdf += r.error[0];
    }
    return MT_OK;
}

/* Integrates pdf and f|cos| over every cell. */
static mt_status integrate_cells(const pass *p, const cf_config *cfg, const long *counts, long n,
                                 double abs_tol, double *pdf_cells, double *fcos, double *gap, double *err_total,
                                 mt_error *err)
{
    int ncell = cfg->nphi * cfg->nz, c, k;
    fcos[0] = fcos[1] = fcos[2] = 0;
    gap[0] = gap[1] = gap[2] = 0;
    *err_total = 0;
    for (c = 0; c < ncell; ++c) {
        double v[7], e;
        mt_status st = cf_integrate_cell(cf_bsdf_integrand, (void *)p, cfg, c, counts[c], n, abs_tol, v, &e, err);
        if (st) return st;
        pdf_cells[c] = v[0];
        for (k = 0; k < 3; ++k) {
            fcos[k] += v[1 + k];
            gap[k] += v[4 + k];
        }
        *err_total += e;
    }
    return MT_OK;
}

/* The chi-square of sample counts against expected cell probabilities:
 * cells below 5 expected pooled, the samples that did not land in a cell
 * (failed, or a delta lobe's) one more cell whose probability is what the
 * pdf's integral leaves; a sample in a cell of probability 0 is a hard
 * failure (p = -1). */
void cf_chi2_cells(const cf_config *cfg, const long *counts, const double *pdfc, long n, long in_cells,
                   double integral, cf_chi2 *out)
{
    int ncell = cfg->nphi * cfg->nz, c;
    double chi2 = 0, pool_o = 0, pool_e = 0, e_fail;
    long bins = 0;
    memset(out, 0, sizeof *out);
    for (c = 0; c < ncell; ++c) {
        double e = pdfc[c] * n, o = (double)counts[c];
        if (pdfc[c] <= 0 && o > 0) {
            out->hard = 1;
            out->hard_count += o;
            out->hard_cell = c;
        }
        if (e < 5) {
            pool_o += o;
            pool_e += e;
        } else {
            chi2 += (o - e) * (o - e) / e;
            bins++;
        }
    }
    e_fail = fmax(0, (1 - integral) * n);
    if (e_fail < 5) {
        pool_o += n - in_cells;
        pool_e += e_fail;
    } else {
        chi2 += ((n - in_cells) - e_fail) * ((n - in_cells) - e_fail) / e_fail;
        bins++;
    }
    if (pool_e > 0) {
        chi2 += (pool_o - pool_e) * (pool_o - pool_e) / pool_e;
        bins++;
    }
    out->chi2 = chi2;
    out->dof = bins - 1;
    out->p = out->hard ? -1 : bins > 1 ? cf_chi2_pvalue(chi2, (double)(bins - 1)) : 1;
}

/* Sum of the delta lobes' weights f |cos| (they ignore u1 and u2): each is
 * sampled once through the BSDF, whose pdf is 1 / (number of delta lobes). */
static mt_rgb delta_rho(const mt_bsdf *b, mt_vec3 wo)
{
    const unsigned spec = MT_BSDF_REFLECTION | MT_BSDF_TRANSMISSION | MT_BSDF_SPECULAR;
    int k, nspec = mt_bsdf_num_components(b, spec);
    mt_rgb r = mt_rgb_black();
    for (k = 0; k < nspec; ++k) {
        mt_bsdf_sample s = mt_bsdf_sample_f(b, wo, (mt_real)((k + 0.5) / nspec), 0.5f, 0.5f, spec);
        if (s.pdf > 0) r = mt_rgb_add(r, mt_rgb_scale(s.f, mt_fabs(s.wi.z) / (s.pdf * nspec)));
    }
    return r;
}

typedef struct wo_stats {
    double id_rel, id_ulps;     /* worst identity deviation */
    long id_bad;                /* samples that broke an invariant */
    char id_what[128];
    double chi2_p;              /* p-value, or -1 for a hard failure */
    long chi2_dof;
    double integral, success, integral_tol;
    double mc[3], mc_se[3], quad[3], quad_err;
    double gap[3]; /* the part of quad no sample can reach */
} wo_stats;

static double rel(double a, double b)
{
    double m = fmax(fabs(a), fabs(b));
    return m > 0 ? fabs(a - b) / m : 0;
}

/* One incoming direction: the pass of samples and the derived statistics. */
static mt_status one_wo(const cf_subject *s, const mt_bsdf *b, mt_vec3 wo, unsigned flags, int density,
                        const cf_config *cfg, uint64_t seed, wo_stats *st, mt_error *err)
{
    long n = cfg->samples, i, succ = 0, *counts = NULL;
    int ncell = cfg->nphi * cfg->nz, c;
    double *pdfc = NULL, sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0}, fcos[3], cerr = 0;
    mt_rng rng;
    pass p;
    mt_status ret = MT_OK;
    memset(st, 0, sizeof *st);
    st->chi2_p = 1;
    counts = calloc((size_t)ncell, sizeof *counts);
    pdfc = calloc((size_t)ncell, sizeof *pdfc);
    if (!counts || !pdfc) {
        free(counts);
        free(pdfc);
        return mt_error_set(err, MT_ERR_NOMEM, "conformance: out of memory");
    }
    mt_rng_seed(&rng, seed, 77);
    for (i = 0; i < n; ++i) {
        mt_real uc = mt_rng_uniform(&rng), u1 = mt_rng_uniform(&rng), u2 = mt_rng_uniform(&rng);
        mt_bsdf_sample sm = mt_bsdf_sample_f(b, wo, uc, u1, u2, flags);
        int k;
        if (!(sm.pdf > 0)) {
            if (sm.pdf != 0 || !mt_rgb_is_finite(sm.f)) {
                st->id_bad++;
                snprintf(st->id_what, sizeof st->id_what, "pdf %g on failure", (double)sm.pdf);
            }
            continue;
        }
        succ++;
        if (!mt_v3_is_finite(sm.wi) || fabs(mt_v3_len(sm.wi) - 1) > 64 * EPS || !mt_rgb_is_finite(sm.f) ||
            mt_rgb_min(sm.f) < 0 || !mt_is_finite(sm.pdf)) {
            st->id_bad++;
            snprintf(st->id_what, sizeof st->id_what, "invalid sample (|wi|-1 = %.2g, f %g, pdf %g)",
                     (double)mt_v3_len(sm.wi) - 1, (double)sm.f.c[0], (double)sm.pdf);
            continue;
        }
        counts[cf_cell_of(cfg, sm.wi)]++;
        for (k = 0; k < 3; ++k) {
            double w = sm.f.c[k] * fabs(sm.wi.z) / sm.pdf;
            sum[k] += w;
            sum2[k] += w * w;
        }
        if (!(sm.type & MT_BSDF_SPECULAR) && i < 50000) {
            mt_real pe = mt_bsdf_pdf(b, wo, sm.wi, flags);
            mt_rgb fe = mt_bsdf_f(b, wo, sm.wi, flags);
            double r = rel(sm.pdf, pe), u = t_ulps(sm.pdf, pe);
            for (k = 0; k < 3; ++k) {
                double rf = rel(sm.f.c[k], fe.c[k]);
                if (rf > r) {
                    r = rf;
                    u = t_ulps(sm.f.c[k], fe.c[k]);
                }
            }
            if (r > st->id_rel) {
                st->id_rel = r;
                snprintf(st->id_what, sizeof st->id_what, "pdf %.6g vs Pdf() %.6g", (double)sm.pdf, (double)pe);
            }
            if (u > st->id_ulps) st->id_ulps = u;
        }
    }
    for (c = 0; c < 3; ++c) {
        double m = sum[c] / n, var = sum2[c] / n - m * m;
        st->mc[c] = m;
        st->mc_se[c] = sqrt(fmax(var, 0) / n);
    }
    st->success = (double)succ / n;
    fcos[0] = fcos[1] = fcos[2] = 0;
    if (density) {
        p.bsdf = b;
        p.wo = wo;
        p.flags = flags;
        ret = integrate_cells(&p, cfg, counts, n, 0.05 / ((double)n * ncell), pdfc, fcos, st->gap, &cerr, err);
        if (ret) goto done;
        st->integral = 0;
        for (c = 0; c < ncell; ++c) st->integral += pdfc[c];
        st->quad_err = cerr;
        {
            cf_chi2 x;
            cf_chi2_cells(cfg, counts, pdfc, n, succ, st->integral, &x);
            if (x.hard)
                snprintf(st->id_what, sizeof st->id_what, "%.0f samples in a cell with Pdf() = 0", x.hard_count);
            st->chi2_p = x.p;
            st->chi2_dof = x.dof;
        }
        st->integral_tol = cf_normal_two_sided_z(cfg->alpha_test) *
                               sqrt(fmax(st->success * (1 - st->success), 1.0 / n) / n) +
                           cerr + noise_allowance(s);
    }
    {
        mt_rgb d = (flags & MT_BSDF_SPECULAR) ? delta_rho(b, wo) : mt_rgb_black();
        for (c = 0; c < 3; ++c) st->quad[c] = fcos[c] + d.c[c];
    }
done:
    free(counts);
    free(pdfc);
    return ret;
}

static void set(cf_result *r, int ok, double stat, const char *bound, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 5, 6)))
#endif
    ;
static void set(cf_result *r, int ok, double stat, const char *bound, const char *fmt, ...)
{
    va_list ap;
    r->ok = ok;
    r->stat = stat;
    snprintf(r->bound, sizeof r->bound, "%s", bound);
    va_start(ap, fmt);
    vsnprintf(r->statistic, sizeof r->statistic, fmt, ap);
    va_end(ap);
}

static int has_density(const mt_bsdf *b)
{
    int i;
    for (i = 0; i < mt_bsdf_count(b); ++i)
        if (!(mt_bxdf_type(mt_bsdf_component(b, i)) & MT_BSDF_SPECULAR)) return 1;
    return 0;
}

static int has_delta(const mt_bsdf *b)
{
    int i;
    for (i = 0; i < mt_bsdf_count(b); ++i)
        if (mt_bxdf_type(mt_bsdf_component(b, i)) & MT_BSDF_SPECULAR) return 1;
    return 0;
}

mt_status cf_sampling_checks(const cf_subject *s, mt_mode mode, const cf_config *cfg,
                             cf_sample_report *rep, mt_error *err)
{
    mt_vec3 wos[MAXWO];
    int nwo = cf_wo_set(s, wos, MAXWO), w, k;
    mt_arena *a = mt_arena_create(0);
    mt_bsdf *b;
    mt_status st;
    double worst_id = 0, worst_ulps = 0, min_p = 1, worst_int = 0, worst_mc = 0, worst_bound = 0, worst_gap = 0;
    int cover_ok = 1;
    char gapwhat[96] = "";
    long bad = 0, dof = 0;
    int id_ok = 1, chi_ok = 1, int_ok = 1, mc_ok = 1, bound_ok = 1;
    char what[128] = "", mcwhat[96] = "", boundwhat[96] = "", intwhat[96] = "";
    double z = cf_normal_two_sided_z(cfg->alpha_test), allow = noise_allowance(s);
    /* Sample_f and Pdf compute cos(theta_h) differently (the sampled value
     * and the normalized wo + wi); raised to the exponent e its rounding
     * error grows e times, so the identity holds to IDENTITY_TOL or that. */
    double id_tol = fmax(IDENTITY_TOL, allow);
    char id_bound[32];
    memset(rep, 0, sizeof *rep);
    rep->rho_min = 1e300;
    rep->rho_max = -1e300;
    if (!a) return mt_error_set(err, MT_ERR_NOMEM, "conformance: out of memory");
    if ((st = s->build(s, a, mode, &b, err)) != MT_OK) {
        mt_arena_destroy(a);
        return st;
    }
    rep->has_density = has_density(b) && !(s->flags & CF_NO_CHI2);
    for (w = 0; w < nwo; ++w) {
        wo_stats ws, wsd;
        uint64_t seed = 0x9e3779b97f4a7c15ULL * (uint64_t)(w + 1);
        for (k = 0; s->name[k]; ++k) seed = seed * 31 + (unsigned char)s->name[k];
        /* with delta lobes too, the density checks use the other components */
        st = one_wo(s, b, wos[w], has_delta(b) ? MT_BSDF_ALL & ~(unsigned)MT_BSDF_SPECULAR : MT_BSDF_ALL,
                    rep->has_density, cfg, seed, &wsd, err);
        if (st) break;
        if (has_delta(b)) {
            st = one_wo(s, b, wos[w], MT_BSDF_ALL, 0, cfg, seed + 1, &ws, err);
            if (st) break;
            for (k = 0; k < 3; ++k) {
                ws.quad[k] += wsd.quad[k]; /* add the density part */
                ws.gap[k] = wsd.gap[k];
            }
            ws.quad_err = wsd.quad_err;
            ws.id_rel = fmax(ws.id_rel, wsd.id_rel);
            ws.id_ulps = fmax(ws.id_ulps, wsd.id_ulps);
            ws.id_bad += wsd.id_bad;
        } else {
            ws = wsd;
        }
        /* identity */
        worst_id = fmax(worst_id, ws.id_rel);
        worst_ulps = fmax(worst_ulps, ws.id_ulps);
        bad += ws.id_bad;
        if (ws.id_bad || ws.id_rel > id_tol) {
            id_ok = 0;
            snprintf(what, sizeof what, "%s", ws.id_what);
        }
        /* chi-square and integral */
        if (rep->has_density) {
            if (wsd.chi2_p < min_p) {
                min_p = wsd.chi2_p;
                dof = wsd.chi2_dof;
            }
            if (wsd.chi2_p < cfg->alpha_test) chi_ok = 0;
            if (fabs(wsd.integral - wsd.success) > wsd.integral_tol) int_ok = 0;
            if (fabs(wsd.integral - wsd.success) / wsd.integral_tol > worst_int) {
                worst_int = fabs(wsd.integral - wsd.success) / wsd.integral_tol;
                snprintf(intwhat, sizeof intwhat, "int %.6f vs success %.6f", wsd.integral, wsd.success);
            }
        }
        /* furnace: quadrature against the sampler's Monte Carlo estimate,
         * which only sees the part of f where the pdf is not 0 */
        for (k = 0; k < 3; ++k) {
            double gap_tol = ws.quad_err + allow * fabs(ws.quad[k]) + 1e-6;
            if (ws.gap[k] > gap_tol && !(s->flags & CF_SHADING_GAP)) {
                cover_ok = 0;
                snprintf(gapwhat, sizeof gapwhat, "f > 0 where pdf = 0: %.4g of rho unreachable", ws.gap[k]);
            }
            worst_gap = fmax(worst_gap, ws.gap[k]);
        }
        for (k = 0; k < 3; ++k) {
            /* the Monte Carlo sum of n terms carries n eps of rounding */
            double q = ws.quad[k] - ws.gap[k], tol = z * ws.mc_se[k] + ws.quad_err + allow * fabs(q) +
                                         (double)cfg->samples * DBL_EPSILON * fabs(q) + 1e-12;
            double dev = fabs(ws.mc[k] - q) / tol;
            if (dev > 1) mc_ok = 0;
            if (dev > worst_mc) {
                worst_mc = dev;
                snprintf(mcwhat, sizeof mcwhat, "quad %.6f MC %.6f +- %.1g", q, ws.mc[k], ws.mc_se[k]);
            }
            rep->rho_min = fmin(rep->rho_min, q);
            rep->rho_max = fmax(rep->rho_max, q);
        }
        /* furnace expectation */
        for (k = 0; k < 3; ++k) {
            double q = ws.quad[k], excess = 0;
            if (s->flags & CF_FURNACE_EXACT) excess = fabs(q - s->expect_rho) - (allow + 1e-6);
            if (s->flags & CF_FURNACE_LE1) excess = q - (1 + allow + 1e-6);
            if (s->flags & CF_FURNACE_LE) excess = q - (s->expect_rho + allow + 1e-6);
            if (excess > 0) bound_ok = 0;
            if (excess > worst_bound || !boundwhat[0]) {
                worst_bound = fmax(worst_bound, excess);
                snprintf(boundwhat, sizeof boundwhat, "rho %.6f at cos %.3g", q, (double)wos[w].z);
            }
        }
    }
    mt_arena_destroy(a);
    if (st) return st;
    snprintf(id_bound, sizeof id_bound, "rel <= %.2g", id_tol);
    set(&rep->identity, id_ok, worst_id, id_bound,
        "max rel %.2g (%.0f ulps), %ld invalid%s%s", worst_id, worst_ulps, bad, id_ok ? "" : ": ",
        id_ok ? "" : what);
    if (rep->has_density) {
        char bound[64];
        snprintf(bound, sizeof bound, "p >= %.2g", cfg->alpha_test);
        if (min_p < 0)
            set(&rep->chi2, 0, min_p, bound, "hard failure: %s", what);
        else
            set(&rep->chi2, chi_ok, min_p, bound, "min p %.3g (%ld dof)", min_p, dof);
        set(&rep->integral, int_ok, worst_int, "dev/tol <= 1", "dev/tol %.2f (%s)", worst_int, intwhat);
    }
    if (!cover_ok)
        set(&rep->furnace_mc, 0, worst_gap, "pdf covers f", "%s", gapwhat);
    else if (worst_gap > 0 && (s->flags & CF_SHADING_GAP))
        set(&rep->furnace_mc, mc_ok, worst_mc, "dev/tol <= 1", "dev/tol %.2f (%s; unreachable %.3g)", worst_mc, mcwhat,
            worst_gap);
    else
        set(&rep->furnace_mc, mc_ok, worst_mc, "dev/tol <= 1", "dev/tol %.2f (%s)", worst_mc, mcwhat);
    {
        char bound[64] = "report";
        if (s->flags & CF_FURNACE_EXACT) snprintf(bound, sizeof bound, "rho = %g", s->expect_rho);
        if (s->flags & CF_FURNACE_LE1) snprintf(bound, sizeof bound, "rho <= 1 (+%.1g)", allow);
        if (s->flags & CF_FURNACE_LE) snprintf(bound, sizeof bound, "rho <= %g", s->expect_rho);
        set(&rep->furnace_bound, bound_ok, worst_bound, bound, "rho %.6f..%.6f (%s)", rep->rho_min,
            rep->rho_max, boundwhat);
    }
    return MT_OK;
}
