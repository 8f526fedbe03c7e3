/*
 * The checks --impl runs on one configuration, from the implementation's
 * answers (test) and materia's in-process (ref):
 *
 *  identity      a sample's f and pdf equal eval at the direction returned;
 *                the sample is finite, f >= 0, pdf >= 0, wi unit
 *  chi2          its sampled directions against its own pdf over the sphere
 *                (the suite's cells, adaptive cubature of eval's pdf, pooling,
 *                Sidak: sampling.c's code)
 *  pdf integral  its pdf's integral against the fraction of its samples that
 *                land in a cell (succeed and are not a delta lobe's)
 *  chi2 materia  its sampled directions against materia's pdf
 *  furnace MC=quad, furnace
 *                the albedo by quadrature of its f |cos| (plus its delta
 *                samples' weights) against its Monte Carlo estimate, and
 *                <= 1 where the configuration conserves energy
 *  agree f, agree pdf
 *                eval against materia's, within a tolerance derived at each
 *                query (below)
 *  agree delta   the delta lobes' directions and f against materia's
 *  reciprocity   f(wo, wi) = f(wi, wo)
 *  helmholtz     specular transmission: T(T(w)) = w and the weights in either
 *                convention (pbrt-v2's, or radiance's (eta_i/eta_o)^2)
 *  extremes      no NaN, Inf or negative value on the extremes grid
 *
 * The tolerance of a comparison with materia: an implementation computing in
 * float differs from the exact answer by its roundings, which act like
 * relative perturbations of a few float epsilons of its inputs and
 * intermediate values. So at every query materia is evaluated with wo, then
 * wi, rotated by 4 float epsilons four ways (towards +-t1, +-t2, two
 * directions perpendicular to it), and the bound is 4 times the largest
 * change this makes, plus
 * 64 float epsilons of the value and 1e-6 of the largest value of the
 * configuration (where a tail underflows in float). A sharp lobe (cos^e) or
 * Fresnel near total internal reflection then gets the wide bound its
 * conditioning asks for, a Lambertian 64 epsilons.
 */
#include <float.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "impl.h"

#define EPSF ((double)FLT_EPSILON)
#define MAXWO 8
#define NSTRATA 32

const char *const cf_impl_check_names[CK_NCHECK] = {
    "identity", "chi2", "pdf integral", "chi2 materia", "furnace MC=quad", "furnace", "agree f",
    "agree pdf", "agree delta", "reciprocity", "helmholtz", "extremes"};

static void set(cf_impl_result *r, int ok, const char *bound, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;
#include <stdarg.h>
static void set(cf_impl_result *r, int ok, const char *bound, const char *fmt, ...)
{
    va_list ap;
    r->ok = ok;
    snprintf(r->bound, sizeof r->bound, "%s", bound);
    va_start(ap, fmt);
    vsnprintf(r->statistic, sizeof r->statistic, fmt, ap);
    va_end(ap);
}

void cf_worst_add(cf_worst *list, double score, const char *query, const char *expected, const char *got)
{
    int i, j;
    for (i = 0; i < CI_WORST; ++i)
        if (!list[i].query[0] || score > list[i].score) break;
    if (i == CI_WORST) return;
    for (j = CI_WORST - 1; j > i; --j) list[j] = list[j - 1];
    list[i].score = score;
    snprintf(list[i].query, sizeof list[i].query, "%s", query);
    snprintf(list[i].expected, sizeof list[i].expected, "%s", expected);
    snprintf(list[i].got, sizeof list[i].got, "%s", got);
}

static mt_vec3 fl(mt_vec3 v) { return mt_v3((mt_real)(float)v.x, (mt_real)(float)v.y, (mt_real)(float)v.z); }

static mt_vec3 fl3(const double *v) { return mt_v3((mt_real)(float)v[0], (mt_real)(float)v[1], (mt_real)(float)v[2]); }

static double rel(double a, double b)
{
    double m = fmax(fabs(a), fabs(b));
    return m > 1e-30 ? fabs(a - b) / m : 0;
}

static int finite_nonneg(double x) { return isfinite(x) && x >= 0; }

/* Finite, f >= 0 and pdf >= 0, and when the pdf is > 0 a wi of unit length
 * (to tol). */
static int sample_valid(const cf_samp *x, double tol)
{
    double len = sqrt(x->wi[0] * x->wi[0] + x->wi[1] * x->wi[1] + x->wi[2] * x->wi[2]);
    int ok = finite_nonneg(x->pdf), k;
    for (k = 0; k < 3; ++k) ok &= finite_nonneg(x->f[k]) && isfinite(x->wi[k]);
    return ok && (!(x->pdf > 0) || fabs(len - 1) <= tol);
}

static void q_eval(char *q, size_t n, mt_vec3 wo, mt_vec3 wi)
{
    snprintf(q, n, "eval %.9g %.9g %.9g %.9g %.9g %.9g", (double)wo.x, (double)wo.y, (double)wo.z, (double)wi.x,
             (double)wi.y, (double)wi.z);
}

static void q_sample(char *q, size_t n, mt_vec3 wo, const float *u)
{
    snprintf(q, n, "sample %.9g %.9g %.9g %.9g %.9g %.9g", (double)wo.x, (double)wo.y, (double)wo.z, (double)u[0],
             (double)u[1], (double)u[2]);
}

static void a_eval(char *a, size_t n, const cf_eval *e)
{
    snprintf(a, n, "%.9g %.9g %.9g %.9g", e->f[0], e->f[1], e->f[2], e->pdf);
}

static void a_sample(char *a, size_t n, const cf_samp *s)
{
    snprintf(a, n, "%.9g %.9g %.9g %.9g %.9g %.9g %.9g %u", s->wi[0], s->wi[1], s->wi[2], s->f[0], s->f[1], s->f[2],
             s->pdf, s->flags);
}

/* The suite's incoming directions: cos theta 0.9999, 0.7, 0.3, 0.03 (the
 * first `per_side` of them, grazing kept), below too when two-sided. */
static int wo_set(const cf_impl_config *c, int per_side, mt_vec3 *wo)
{
    static const double cosines[] = {0.9999, 0.7, 0.3, 0.03};
    static const int quick[] = {1, 3};
    int n = 0, k, side, sides = (c->flags & CI_TWO_SIDED) ? 2 : 1;
    for (side = 0; side < sides; ++side)
        for (k = 0; k < per_side && k < 4; ++k) {
            int i = per_side >= 4 ? k : quick[k % 2];
            double cz = cosines[i], s = sqrt(1 - cz * cz), phi = 0.7 + 1.3 * i;
            wo[n++] = fl(mt_v3((mt_real)(s * cos(phi)), (mt_real)(s * sin(phi)), (mt_real)(side ? -cz : cz)));
        }
    return n;
}

/* A uniform number in [0, 1) as the float the query line carries: the
 * double build's uniform can round up to 1.0f (about one in 2^25; the
 * protocol rightly refuses u = 1), so it stops at the float below 1. The
 * float build's uniform is already such a float: the same numbers. */
static float u_float(mt_rng *rng)
{
    float u = (float)mt_rng_uniform(rng);
    return u < 1 ? u : 0x1.fffffep-1f;
}

static uint64_t seed_of(const char *name, int k)
{
    uint64_t s = 0x9e3779b97f4a7c15ULL * (uint64_t)(k + 1);
    for (; *name; ++name) s = s * 31 + (unsigned char)*name;
    return s;
}

static int has_kind(const mt_bsdf *b, unsigned need, unsigned without)
{
    int i;
    for (i = 0; i < mt_bsdf_count(b); ++i) {
        unsigned t = mt_bxdf_type(mt_bsdf_component(b, i));
        if ((t & need) == need && !(t & without)) return 1;
    }
    return 0;
}

/* ---- the cubature of an implementation's eval, in rounds --------------- */
/* mt_cubature asks for one value at a time; a child answers best in big
 * batches. So each cell's cubature runs on a cache of answers: a node not in
 * it is recorded and counts as 0, and the cell is done once a run needed no
 * such node. The missing nodes of every cell are then asked in one batch and
 * the unfinished cells run again; the last run of each cell is exactly the
 * cubature of the implementation's own values. */
typedef struct cache {
    float *key;    /* 3 per slot */
    double *val;   /* 4 per slot: f rgb, pdf */
    unsigned char *state; /* 0 empty, 1 asked, 2 answered */
    size_t cap, n;
    mt_vec3 *miss;
    size_t nmiss, cap_miss;
} cache;

static size_t hash3(const float *k)
{
    uint32_t b[3];
    uint64_t h;
    memcpy(b, k, sizeof b);
    /* splitmix64's finalizer: every key bit reaches the low bits */
    h = ((uint64_t)b[0] << 32 | b[1]) ^ ((uint64_t)b[2] * 0x9e3779b97f4a7c15ULL);
    h = (h ^ (h >> 30)) * 0xbf58476d1ce4e5b9ULL;
    h = (h ^ (h >> 27)) * 0x94d049bb133111ebULL;
    return (size_t)(h ^ (h >> 31));
}

static size_t find_slot(const cache *c, const float *k)
{
    size_t h = hash3(k) & (c->cap - 1);
    while (c->state[h] && memcmp(c->key + 3 * h, k, 3 * sizeof *k)) h = (h + 1) & (c->cap - 1);
    return h;
}

static int cache_grow(cache *c)
{
    cache n;
    size_t i;
    memset(&n, 0, sizeof n);
    n.cap = c->cap ? 2 * c->cap : 1 << 16;
    n.key = malloc(n.cap * 3 * sizeof *n.key);
    n.val = malloc(n.cap * 4 * sizeof *n.val);
    n.state = calloc(n.cap, 1);
    if (!n.key || !n.val || !n.state) {
        free(n.key);
        free(n.val);
        free(n.state);
        return -1;
    }
    for (i = 0; i < c->cap; ++i)
        if (c->state[i]) {
            size_t h = hash3(c->key + 3 * i) & (n.cap - 1);
            while (n.state[h]) h = (h + 1) & (n.cap - 1);
            memcpy(n.key + 3 * h, c->key + 3 * i, 3 * sizeof *n.key);
            memcpy(n.val + 4 * h, c->val + 4 * i, 4 * sizeof *n.val);
            n.state[h] = c->state[i];
        }
    free(c->key);
    free(c->val);
    free(c->state);
    c->key = n.key;
    c->val = n.val;
    c->state = n.state;
    c->cap = n.cap;
    return 0;
}

typedef struct ccb {
    cache *c;
    mt_vec3 wo;
    int missing, oom;
} ccb;

static void cached_integrand(void *ctx, double phi, double z, double *out)
{
    ccb *b = ctx;
    cache *c = b->c;
    mt_vec3 d = fl(mt_sphere_direction(phi, z));
    float k[3];
    size_t h;
    int i;
    for (i = 0; i < 7; ++i) out[i] = 0;
    k[0] = (float)d.x;
    k[1] = (float)d.y;
    k[2] = (float)d.z;
    if (2 * (c->n + 1) > c->cap && cache_grow(c)) {
        b->oom = 1;
        return;
    }
    h = find_slot(c, k);
    if (c->state[h] == 2) {
        const double *v = c->val + 4 * h;
        double cz = fabs(z), pdf = v[3];
        out[0] = pdf;
        for (i = 0; i < 3; ++i) {
            out[1 + i] = v[i] * cz;
            out[4 + i] = pdf > 0 ? 0 : v[i] * cz;
        }
        return;
    }
    b->missing = 1;
    if (c->state[h] == 1) return;
    if (c->nmiss == c->cap_miss) {
        size_t nc = c->cap_miss ? 2 * c->cap_miss : 4096;
        mt_vec3 *m = realloc(c->miss, nc * sizeof *m);
        if (m) c->miss = m;
        if (!m) {
            b->oom = 1;
            return;
        }
        c->cap_miss = nc;
    }
    memcpy(c->key + 3 * h, k, sizeof k);
    c->state[h] = 1;
    c->n++;
    c->miss[c->nmiss++] = d;
}

static void cache_free(cache *c)
{
    free(c->key);
    free(c->val);
    free(c->state);
    free(c->miss);
}

/* Cell integrals of the implementation's eval at wo: pdfc[cell] and the
 * totals of f |cos| and of its part where the pdf is 0. -1 on protocol
 * failure, -2 out of memory. */
static int impl_cells(cf_impl *im, const cf_config *cfg, mt_vec3 wo, const long *counts, long n, double *pdfc,
                      double fcos[3], double gap[3], double *cerr)
{
    int ncell = cfg->nphi * cfg->nz, c, k, r = 0;
    unsigned char *done = calloc((size_t)ncell, 1);
    double abs_tol = 0.05 / ((double)n * ncell);
    cache ch;
    ccb b;
    mt_vec3 *wos = NULL;
    cf_eval *ev = NULL;
    size_t cap = 0;
    memset(&ch, 0, sizeof ch);
    b.c = &ch;
    b.wo = wo;
    b.oom = 0;
    if (!done) return -2;
    for (k = 0; k < 3; ++k) fcos[k] = gap[k] = 0;
    *cerr = 0;
    for (;;) {
        int left = 0;
        size_t i;
        for (c = 0; c < ncell; ++c) {
            double v[7], e;
            mt_error err;
            if (done[c]) continue;
            b.missing = 0;
            mt_error_clear(&err);
            if (cf_integrate_cell(cached_integrand, &b, cfg, c, counts[c], n, abs_tol, v, &e, &err) || b.oom) {
                r = -2;
                goto out;
            }
            if (b.missing) {
                left = 1;
                continue;
            }
            done[c] = 1;
            pdfc[c] = v[0];
            for (k = 0; k < 3; ++k) {
                fcos[k] += v[1 + k];
                gap[k] += v[4 + k];
            }
            *cerr += e;
        }
        if (!left) break;
        if (ch.nmiss > cap) {
            cap = ch.nmiss;
            free(wos);
            free(ev);
            wos = malloc(cap * sizeof *wos);
            ev = malloc(cap * sizeof *ev);
            if (!wos || !ev) {
                r = -2;
                goto out;
            }
        }
        for (i = 0; i < ch.nmiss; ++i) wos[i] = wo;
        if (cf_impl_eval(im, (int)ch.nmiss, wos, ch.miss, ev)) {
            r = -1;
            goto out;
        }
        for (i = 0; i < ch.nmiss; ++i) {
            /* the slot again: the table may have grown since the miss */
            float key[3];
            size_t h;
            double *v;
            key[0] = (float)ch.miss[i].x;
            key[1] = (float)ch.miss[i].y;
            key[2] = (float)ch.miss[i].z;
            h = find_slot(&ch, key);
            v = ch.val + 4 * h;
            for (k = 0; k < 3; ++k) v[k] = isfinite(ev[i].f[k]) ? ev[i].f[k] : 0;
            v[3] = isfinite(ev[i].pdf) ? ev[i].pdf : 0;
            ch.state[h] = 2;
        }
        ch.nmiss = 0;
    }
out:
    free(done);
    free(wos);
    free(ev);
    cache_free(&ch);
    return r;
}

static int ref_cells(const cf_impl *ref, const cf_config *cfg, mt_vec3 wo, const long *counts, long n, double *pdfc)
{
    int ncell = cfg->nphi * cfg->nz, c;
    cf_bsdf_pass p;
    p.bsdf = ref->bsdf;
    p.wo = wo;
    p.flags = MT_BSDF_ALL;
    for (c = 0; c < ncell; ++c) {
        double v[7], e;
        mt_error err;
        mt_error_clear(&err);
        if (cf_integrate_cell(cf_bsdf_integrand, &p, cfg, c, counts[c], n, 0.05 / ((double)n * ncell), v, &e, &err))
            return -2;
        pdfc[c] = v[0];
    }
    return 0;
}

/* ---- materia's conditioning at a query ---------------------------------- */
/* w rotated by 4 float epsilons towards +-t1 (k = 0, 1) or +-t2 (k = 2, 3),
 * two directions perpendicular to it: every way a rounding can move it. */
static mt_vec3 perturb(mt_vec3 w, int k)
{
    double x = w.x, y = w.y, z = w.z, t1[3], t2[3], l, s = (k & 1) ? -4 * EPSF : 4 * EPSF;
    const double *t;
    if (fabs(x) < 0.6) { /* t1 = w x e_x */
        t1[0] = 0;
        t1[1] = z;
        t1[2] = -y;
    } else { /* w x e_y */
        t1[0] = -z;
        t1[1] = 0;
        t1[2] = x;
    }
    l = sqrt(t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]);
    if (!(l > 0)) return w;
    t1[0] /= l;
    t1[1] /= l;
    t1[2] /= l;
    t2[0] = y * t1[2] - z * t1[1];
    t2[1] = z * t1[0] - x * t1[2];
    t2[2] = x * t1[1] - y * t1[0];
    t = k < 2 ? t1 : t2;
    x += s * t[0];
    y += s * t[1];
    z += s * t[2];
    l = sqrt(x * x + y * y + z * z);
    return mt_v3((mt_real)(x / l), (mt_real)(y / l), (mt_real)(z / l));
}

/* v rotated by angle t about the unit axis a (Rodrigues). */
static mt_vec3 rotate(mt_vec3 v, const double a[3], double t)
{
    double c = cos(t), sn = sin(t), d = (a[0] * v.x + a[1] * v.y + a[2] * v.z) * (1 - c);
    double x = v.x * c + (a[1] * v.z - a[2] * v.y) * sn + a[0] * d;
    double y = v.y * c + (a[2] * v.x - a[0] * v.z) * sn + a[1] * d;
    double z = v.z * c + (a[0] * v.y - a[1] * v.x) * sn + a[2] * d;
    return mt_v3((mt_real)x, (mt_real)y, (mt_real)z);
}

/* How far rounding can tilt the shading frame, in radians. The frame is
 * the input n (exact, so 0: the rotations of wo and wi below cover its
 * normalization), except under a bump map: pbrt-v2's Bump() takes the
 * forward difference (d(p + du dpdu) - d(p)) / du, so the roundings of the
 * shifted point and of d (a few eps times 1 + |p|) are divided by the step
 * du (0.01 without differentials, bump.c): measured float against double,
 * `matte with a bump map` at its point tilts by 6e-6 = 50 eps with du
 * 0.01, and this gives 4 eps (1 + |p|) / du = 700 eps there. */
static double frame_tilt(const cf_impl_config *c, const cf_impl *ref)
{
    const mt_diffgeom *dg = mt_bsdf_shading(ref->bsdf);
    double du, dv, p;
    int j, bump = 0;
    for (j = 0; j < CI_MAX_LINES && c->lines[j]; ++j) bump |= strstr(c->lines[j], "bumpmap") != NULL;
    if (!bump) return 0;
    du = 0.5 * (fabs((double)dg->dudx) + fabs((double)dg->dudy));
    dv = 0.5 * (fabs((double)dg->dvdx) + fabs((double)dg->dvdy));
    du = fmin(du > 0 ? du : 0.01, dv > 0 ? dv : 0.01);
    p = sqrt((double)mt_v3_dot(dg->p, dg->p));
    return 4 * EPSF * (1 + p) / du;
}

/* The spread of materia's f and pdf when wo or wi moves by 4 epsilons, and
 * when both turn by the frame's tilt (a tilted frame, seen from the BSDF). */
static void spread(const cf_impl *ref, double tilt, mt_vec3 wo, mt_vec3 wi, const cf_eval *v, double s[4])
{
    int j, k;
    const mt_vec3 n = mt_bsdf_shading(ref->bsdf)->n;
    for (k = 0; k < 4; ++k) s[k] = 0;
    for (j = 0; j < (tilt > 0 ? 12 : 8); ++j) {
        mt_vec3 a = j < 4 ? perturb(wo, j) : wo, b = j >= 4 && j < 8 ? perturb(wi, j - 4) : wi;
        mt_rgb f;
        double p;
        if (j >= 8) { /* about an axis perpendicular to n: perturb(n) - n */
            mt_vec3 t = perturb(n, j < 10 ? 0 : 2);
            double ax[3] = {t.y * n.z - t.z * n.y, t.z * n.x - t.x * n.z, t.x * n.y - t.y * n.x}, l;
            l = sqrt(ax[0] * ax[0] + ax[1] * ax[1] + ax[2] * ax[2]);
            if (!(l > 0)) continue;
            for (k = 0; k < 3; ++k) ax[k] /= l;
            a = rotate(wo, ax, (j & 1) ? -tilt : tilt);
            b = rotate(wi, ax, (j & 1) ? -tilt : tilt);
        }
        f = mt_bsdf_f(ref->bsdf, a, b, MT_BSDF_ALL);
        p = mt_bsdf_pdf(ref->bsdf, a, b, MT_BSDF_ALL);
        for (k = 0; k < 3; ++k) s[k] = fmax(s[k], fabs(f.c[k] - v->f[k]));
        s[3] = fmax(s[3], fabs(p - v->pdf));
    }
}

/* 4 times the spread, the roundings of the value itself (rel: 64 eps, and 3
 * e eps for a lobe cos^e, whose cos theta_h rounds by an eps that the power
 * multiplies by e; noise_allowance), and 1e-6 of the configuration's
 * largest value (a tail that underflows in float). */
static double bound(double v, double s, double rel, double vmax) { return 4 * s + rel * fabs(v) + 1e-6 * vmax + 1e-30; }

/* ---- the checks ------------------------------------------------------------ */
typedef struct acc {
    /* identity */
    long id_bad, id_tested;
    double id_worst;
    /* chi2 / integral / furnace */
    struct {
        double min_p;
        long dof;
        int hard;
    } chi[2]; /* chi2 (its own pdf), chi2 materia */
    double worst_int, worst_mc, worst_excess, rho_lo, rho_hi, worst_gap;
    int gap_bad;
    char int_what[96], mc_what[96], rho_what[96], gap_what[96];
} acc;

static double noise_allowance(const cf_impl_config *c)
{
    double e = c->lobe_exponent > 1 ? c->lobe_exponent : 1;
    return 3 * e * EPSF + 64 * EPSF;
}

/* --plots: the picture of a chi-square of wo number w. */
static void plot(const cf_impl_run *run, const cf_impl_config *c, const char *check, mt_vec3 wo, int w,
                 const long *counts, const double *pdfc, const cf_chi2 *x, const char *label)
{
    char path[4096], slug[128], title[256], sub[256];
    mt_error err;
    size_t i, j = 0;
    if (!run->plots || !(run->plots_all || x->p < run->cfg.alpha_test)) return;
    for (i = 0; c->name[i] && j < sizeof slug - 1; ++i) {
        char ch = c->name[i];
        slug[j++] = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '.' ? ch : '_';
    }
    slug[j] = 0;
    snprintf(path, sizeof path, "%.3000s/%s-%s-%s-wo%d.png", run->plots, slug,
             run->mode == MT_MODE_PBRT_V2 ? "pbrt-v2" : "corrected", !strcmp(check, "chi2") ? "chi2" : "chi2-materia", w);
    snprintf(title, sizeof title, "%.100s, %s: %s, p = %.3g %s %.3g (%s)", c->name,
             run->mode == MT_MODE_PBRT_V2 ? "pbrt-v2" : "corrected", check, x->p, x->p < run->cfg.alpha_test ? "<" : ">=",
             run->cfg.alpha_test, x->p < run->cfg.alpha_test ? "FAIL" : "pass");
    snprintf(sub, sizeof sub, "wo = (%.4f, %.4f, %.4f), %ld samples, %d x %d cells, chi2 %.1f, %ld dof", (double)wo.x,
             (double)wo.y, (double)wo.z, run->cfg.samples, run->cfg.nphi, run->cfg.nz, x->chi2, x->dof);
    mt_error_clear(&err);
    if (cf_impl_plot(path, title, sub, label, &run->cfg, counts, pdfc, run->cfg.samples, &err))
        fprintf(stderr, "materia-conformance: --plots: %s: %s\n", path, err.message);
}

/* The chi-square of wo number w's counts against the cells' probabilities
 * pdfc, by its own pdf (which 0) or materia's (1): the worst p over wo, a
 * hard failure, the picture. Returns the sum of pdfc (the pdf's integral). */
static double chi2_wo(const cf_impl_run *run, const cf_impl_config *c, int which, mt_vec3 wo, int w,
                      const long *counts, const double *pdfc, long in_cells, acc *a)
{
    static const char *const check[2] = {"chi2", "chi2 materia"}, *const label[2] = {"expected (own pdf)",
                                                                                    "expected (materia)"};
    double integral = 0;
    int k, ncell = run->cfg.nphi * run->cfg.nz;
    cf_chi2 x;
    for (k = 0; k < ncell; ++k) integral += pdfc[k];
    cf_chi2_cells(&run->cfg, counts, pdfc, run->cfg.samples, in_cells, integral, &x);
    plot(run, c, check[which], wo, w, counts, pdfc, &x, label[which]);
    if (x.hard) a->chi[which].hard = 1;
    if (x.p < a->chi[which].min_p) {
        a->chi[which].min_p = x.p;
        a->chi[which].dof = x.dof;
    }
    return integral;
}

/* A fraction k / n as a measure: its binomial standard error (at least
 * that of one event in n, so that 0 of n still has a tolerance). */
static void measure_fraction(cf_impl_result *r, long k, long n, double at, const char *what)
{
    double p = n > 0 ? (double)k / n : 0;
    cf_measure_add(r, p, n > 0 ? sqrt(fmax(p * (1 - p), 1.0 / n) / n) : 0, 0, at, what);
}

/* The furnace at one wo, one channel: rho (the cubature of f |cos|, with
 * error cerr, plus the delta samples' weights, whose sum over n samples is
 * dsum, of squares dsum2) against 1 + its noise and the rounding allowance;
 * as a measure, the cubature's error counts too. */
static void furnace_rho(acc *a, cf_impl_result *res, double rho, double dsum, double dsum2, long n, double allow,
                        double cerr, double z, mt_vec3 wo)
{
    double dm = dsum / n, se = sqrt(fmax(dsum2 / n - dm * dm, 0) / n), excess = rho - (1 + allow + 1e-6 + z * se);
    a->rho_lo = fmin(a->rho_lo, rho);
    a->rho_hi = fmax(a->rho_hi, rho);
    if (excess > a->worst_excess || !a->rho_what[0]) {
        a->worst_excess = fmax(a->worst_excess, excess);
        snprintf(a->rho_what, sizeof a->rho_what, "rho %.6f at cos %.3g", rho, (double)wo.z);
    }
    cf_measure_add(&res[CK_FURNACE], rho, se, allow + 1e-6 + cerr, wo.z, "the albedo at cos %.3g");
}

/* The sampling checks of one wo. */
static int sampling_wo(const cf_impl_run *run, const cf_impl_config *c, cf_impl *test, cf_impl *ref, mt_vec3 wo,
                       int w, int density, acc *a, cf_impl_result *res)
{
    const cf_config *cfg = &run->cfg;
    long n = cfg->samples, i, in_cells = 0, *counts, invalid = 0, unlike = 0;
    int ncell = cfg->nphi * cfg->nz, k, r = 0, nid = 0;
    float (*u)[3] = malloc((size_t)n * sizeof *u);
    mt_vec3 *wos = malloc((size_t)n * sizeof *wos), *wis = NULL;
    cf_samp *s = malloc((size_t)n * sizeof *s);
    cf_eval *ev = NULL;
    long *idx = NULL;
    double *pdfc = malloc((size_t)ncell * sizeof *pdfc), *pdfm = malloc((size_t)ncell * sizeof *pdfm);
    double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0}, ssum[3] = {0, 0, 0}, ssum2[3] = {0, 0, 0};
    double z = cf_normal_two_sided_z(cfg->alpha_test), allow = noise_allowance(c);
    double id_tol = fmax(1e-3, allow);
    mt_rng rng;
    char q[160], an[200], ex[400], qs[160];
    counts = calloc((size_t)ncell, sizeof *counts);
    if (!u || !wos || !s || !pdfc || !pdfm || !counts) {
        r = -2;
        goto out;
    }
    mt_rng_seed(&rng, seed_of(c->name, w), 77);
    for (i = 0; i < n; ++i) {
        u[i][0] = u_float(&rng);
        u[i][1] = u_float(&rng);
        u[i][2] = u_float(&rng);
        wos[i] = wo;
    }
    if (cf_impl_sample(test, (int)n, wos, (const float(*)[3])u, s)) {
        r = -1;
        goto out;
    }
    wis = malloc((size_t)n * sizeof *wis);
    idx = malloc((size_t)n * sizeof *idx);
    if (!wis || !idx) {
        r = -2;
        goto out;
    }
    for (i = 0; i < n; ++i) {
        const cf_samp *x = s + i;
        if (!sample_valid(x, 1e-5)) {
            invalid++;
            q_sample(q, sizeof q, wo, u[i]);
            a_sample(an, sizeof an, x);
            cf_worst_add(res[CK_IDENTITY].worst, 1e30, q, "finite, f >= 0, pdf >= 0, |wi| = 1", an);
            continue;
        }
        if (!(x->pdf > 0)) continue;
        for (k = 0; k < 3; ++k) {
            double wgt = x->f[k] * fabs(x->wi[2]) / x->pdf;
            if (x->flags & MT_BSDF_SPECULAR) {
                ssum[k] += wgt;
                ssum2[k] += wgt * wgt;
            } else {
                sum[k] += wgt;
                sum2[k] += wgt * wgt;
            }
        }
        if (x->flags & MT_BSDF_SPECULAR) continue;
        in_cells++;
        counts[cf_cell_of(cfg, fl3(x->wi))]++;
        if (nid < 4000) {
            idx[nid] = i;
            wis[nid++] = fl3(x->wi);
        }
    }
    /* identity: eval where the samples went */
    ev = malloc((size_t)(nid ? nid : 1) * sizeof *ev);
    if (!ev) {
        r = -2;
        goto out;
    }
    if (nid && cf_impl_eval(test, nid, wos, wis, ev)) {
        r = -1;
        goto out;
    }
    for (i = 0; i < nid; ++i) {
        const cf_samp *x = s + idx[i];
        double d = rel(x->pdf, ev[i].pdf);
        for (k = 0; k < 3; ++k) d = fmax(d, rel(x->f[k], ev[i].f[k]));
        a->id_tested++;
        if (!(d <= id_tol)) {
            unlike++;
            q_eval(q, sizeof q, wo, wis[i]);
            a_eval(an, sizeof an, ev + i);
            q_sample(qs, sizeof qs, wo, u[idx[i]]);
            snprintf(ex, sizeof ex, "%.9g %.9g %.9g %.9g (the answer to %s)", x->f[0], x->f[1], x->f[2], x->pdf, qs);
            cf_worst_add(res[CK_IDENTITY].worst, isfinite(d) ? d / id_tol : 1e30, q, ex, an);
        }
        if (isfinite(d)) a->id_worst = fmax(a->id_worst, d);
    }
    a->id_bad += invalid + unlike;
    measure_fraction(&res[CK_IDENTITY], invalid, n, wo.z, "the fraction of invalid samples at cos %.3g");
    measure_fraction(&res[CK_IDENTITY], unlike, nid, wo.z, "the fraction of samples unlike eval at cos %.3g");
    cf_measure_hist(&res[CK_CHI2], counts, ncell, n - in_cells, wo.z);
    cf_measure_hist(&res[CK_CHI2_MATERIA], counts, ncell, n - in_cells, wo.z);
    if (density) {
        double fcos[3], gap[3], cerr = 0, integral, succ = (double)in_cells / n, tol, se;
        if ((r = impl_cells(test, cfg, wo, counts, n, pdfc, fcos, gap, &cerr))) goto out;
        integral = chi2_wo(run, c, 0, wo, w, counts, pdfc, in_cells, a);
        se = sqrt(fmax(succ * (1 - succ), 1.0 / n) / n);
        tol = z * se + cerr + allow;
        cf_measure_add(&res[CK_INTEGRAL], integral - succ, se, cerr + allow, wo.z,
                       "the pdf's integral minus the success fraction at cos %.3g");
        if (fabs(integral - succ) / tol > a->worst_int) {
            a->worst_int = fabs(integral - succ) / tol;
            snprintf(a->int_what, sizeof a->int_what, "int %.6f vs %.6f at cos %.3g", integral, succ, (double)wo.z);
        }
        if ((r = ref_cells(ref, cfg, wo, counts, n, pdfm))) goto out;
        chi2_wo(run, c, 1, wo, w, counts, pdfm, in_cells, a);
        for (k = 0; k < 3; ++k) {
            double qd = fcos[k] - gap[k], m = sum[k] / n, se_mc = sqrt(fmax(sum2[k] / n - m * m, 0) / n);
            double sys = cerr + allow * fabs(qd) + (double)n * DBL_EPSILON * fabs(qd) + 1e-12, dev;
            double gap_tol = cerr + allow * fabs(fcos[k]) + 1e-6;
            if (gap[k] > gap_tol && !(c->flags & CI_SHADING_GAP)) {
                a->gap_bad = 1;
                snprintf(a->gap_what, sizeof a->gap_what, "f > 0 where pdf = 0: %.4g of rho unreachable", gap[k]);
            }
            cf_measure_add(&res[CK_FURNACE_MC], gap[k], 0, gap_tol, wo.z, "the albedo where the pdf is 0 at cos %.3g");
            a->worst_gap = fmax(a->worst_gap, gap[k]);
            dev = fabs(m - qd) / (z * se_mc + sys);
            cf_measure_add(&res[CK_FURNACE_MC], m - qd, se_mc, sys, wo.z,
                           "the Monte Carlo albedo minus the quadrature at cos %.3g");
            if (dev > a->worst_mc || !a->mc_what[0]) {
                a->worst_mc = fmax(a->worst_mc, dev);
                snprintf(a->mc_what, sizeof a->mc_what, "quad %.6f MC %.6f +- %.1g at cos %.3g", qd, m, se_mc,
                         (double)wo.z);
            }
            furnace_rho(a, res, fcos[k] + ssum[k] / n, ssum[k], ssum2[k], n, allow, cerr, z, wo);
        }
    } else {
        for (k = 0; k < 3; ++k) furnace_rho(a, res, ssum[k] / n, ssum[k], ssum2[k], n, allow, 0, z, wo);
    }
out:
    free(u);
    free(wos);
    free(wis);
    free(s);
    free(ev);
    free(idx);
    free(pdfc);
    free(pdfm);
    free(counts);
    return r;
}

/* agree f, agree pdf, reciprocity: pairs from the whole sphere and from
 * materia's sampler (where the lobes are). */
static int pair_checks(const cf_impl_config *c, cf_impl *test, cf_impl *ref, const mt_vec3 *wo, int nwo, int density,
                       cf_impl_result *res)
{
    enum { PER = 96 };
    int np = nwo * PER + 512, i, k, m = 0, r = 0;
    mt_vec3 *a = malloc((size_t)np * 2 * sizeof *a), *b = malloc((size_t)np * 2 * sizeof *b);
    cf_eval *et = malloc((size_t)np * 2 * sizeof *et), *er = malloc((size_t)np * 2 * sizeof *er);
    double fmaxv = 0, pmax = 0, worst_f = 0, worst_p = 0, worst_r = 0, rel = noise_allowance(c),
           tilt = frame_tilt(c, ref);
    long bad_f = 0, bad_p = 0, bad_r = 0, nonzero = 0, skipped = 0;
    mt_vec3 ng = mt_bsdf_ng(ref->bsdf), ns = mt_bsdf_shading(ref->bsdf)->n;
    mt_rng rng;
    char q[160], ex[160], got[160];
    if (!a || !b || !et || !er) {
        r = -2;
        goto out;
    }
    mt_rng_seed(&rng, seed_of(c->name, 99), 5);
    for (i = 0; i < nwo; ++i)
        for (k = 0; k < PER; ++k) {
            mt_vec3 wi;
            if (k < PER / 2) {
                wi = mt_uniform_sample_sphere(mt_rng_uniform(&rng), mt_rng_uniform(&rng));
            } else {
                mt_bsdf_sample s = mt_bsdf_sample_f(ref->bsdf, wo[i], mt_rng_uniform(&rng), mt_rng_uniform(&rng),
                                                    mt_rng_uniform(&rng), MT_BSDF_ALL);
                wi = s.pdf > 0 ? s.wi : mt_uniform_sample_sphere(mt_rng_uniform(&rng), mt_rng_uniform(&rng));
            }
            a[m] = wo[i];
            b[m++] = fl(wi);
        }
    for (i = 0; i < 512; ++i) {
        a[m] = fl(mt_uniform_sample_sphere(mt_rng_uniform(&rng), mt_rng_uniform(&rng)));
        b[m++] = fl(mt_uniform_sample_sphere(mt_rng_uniform(&rng), mt_rng_uniform(&rng)));
    }
    for (i = 0; i < m; ++i) { /* the reversed pairs after */
        a[m + i] = b[i];
        b[m + i] = a[i];
    }
    if (cf_impl_eval(test, 2 * m, a, b, et)) {
        r = -1;
        goto out;
    }
    cf_impl_eval(ref, 2 * m, a, b, er);
    for (i = 0; i < 2 * m; ++i) {
        for (k = 0; k < 3; ++k) fmaxv = fmax(fmaxv, fabs(er[i].f[k]));
        pmax = fmax(pmax, fabs(er[i].pdf));
    }
    for (i = 0; i < 2 * m; ++i) {
        double s[4], sr[4], ef = 0, ep;
        spread(ref, tilt, a[i], b[i], er + i, s);
        for (k = 0; k < 3; ++k) {
            double t = bound(er[i].f[k], s[k], rel, fmaxv), e = fabs(et[i].f[k] - er[i].f[k]) / t;
            ef = fmax(ef, isfinite(e) ? e : 1e30);
        }
        ep = fabs(et[i].pdf - er[i].pdf) / bound(er[i].pdf, s[3], rel, pmax);
        if (!isfinite(ep)) ep = 1e30;
        worst_f = fmax(worst_f, ef);
        worst_p = fmax(worst_p, ep);
        if (ef > 1 || ep > 1) {
            q_eval(q, sizeof q, a[i], b[i]);
            a_eval(ex, sizeof ex, er + i);
            a_eval(got, sizeof got, et + i);
            if (ef > 1) {
                bad_f++;
                cf_worst_add(res[CK_AGREE_F].worst, ef, q, ex, got);
            }
            if (ep > 1) {
                bad_p++;
                cf_worst_add(res[CK_AGREE_PDF].worst, ep, q, ex, got);
            }
        }
        /* reciprocity: the test's own f both ways, within the larger bound;
         * not where the shading and geometric normals disagree on whether
         * the pair is reflection (shading normals are not reciprocal) */
        if (i < m && density &&
            (mt_v3_dot(a[i], ng) * mt_v3_dot(b[i], ng) > 0) != (mt_v3_dot(a[i], ns) * mt_v3_dot(b[i], ns) > 0)) {
            skipped++;
        } else if (i < m && density) {
            double e = 0;
            spread(ref, tilt, a[m + i], b[m + i], er + m + i, sr);
            for (k = 0; k < 3; ++k) {
                double t = fmax(bound(er[i].f[k], s[k], rel, fmaxv), bound(er[m + i].f[k], sr[k], rel, fmaxv));
                double d = fabs(et[i].f[k] - et[m + i].f[k]) / t;
                e = fmax(e, isfinite(d) ? d : 1e30);
                nonzero += et[i].f[k] != 0;
                cf_measure_add(&res[CK_RECIPROCITY], et[i].f[k] - et[m + i].f[k], 0, t, i,
                               "f(wo, wi) - f(wi, wo) on pair %g");
            }
            worst_r = fmax(worst_r, e);
            if (e > 1) {
                char e2[200];
                bad_r++;
                q_eval(q, sizeof q, a[i], b[i]);
                a_eval(ex, sizeof ex, et + m + i);
                a_eval(got, sizeof got, et + i);
                snprintf(e2, sizeof e2, "%.60s (its answer to the reverse query)", ex);
                cf_worst_add(res[CK_RECIPROCITY].worst, e, q, e2, got);
            }
        }
    }
    set(&res[CK_AGREE_F], bad_f == 0, "err/tol <= 1", "worst err/tol %.3g, %ld of %d queries off", worst_f, bad_f,
        2 * m);
    set(&res[CK_AGREE_PDF], bad_p == 0, "err/tol <= 1", "worst err/tol %.3g, %ld of %d queries off", worst_p, bad_p,
        2 * m);
    if (density)
        set(&res[CK_RECIPROCITY], bad_r == 0, "err/tol <= 1", "worst err/tol %.3g over %ld pairs (%ld values != 0)%s",
            worst_r, m - skipped, nonzero, skipped ? ", not where n and ng disagree" : "");
out:
    free(a);
    free(b);
    free(et);
    free(er);
    return r;
}

static int is_delta(const cf_samp *x) { return (x->flags & MT_BSDF_SPECULAR) && x->pdf > 0; }

/* A test delta sample against materia's j-th, in units of j's bounds. */
static double delta_err(const cf_samp *t, const cf_samp *m, double tdir, const double *tf)
{
    double d = 0, e;
    int k;
    for (k = 0; k < 3; ++k) d += (t->wi[k] - m->wi[k]) * (t->wi[k] - m->wi[k]);
    e = sqrt(d) / tdir;
    for (k = 0; k < 3; ++k) e = fmax(e, fabs(t->f[k] - m->f[k]) / tf[k]);
    return isfinite(e) ? e : 1e30;
}

/* agree delta: each delta sample of the test is one of materia's (direction
 * and f), and each of materia's lobes carrying 1/16 of the weight is found. */
static int delta_check(const cf_impl_config *c, cf_impl *test, cf_impl *ref, const mt_vec3 *wo, int nwo,
                       cf_impl_result *res)
{
    int n = nwo * NSTRATA, i, j, k, r = 0, bad = 0, tested = 0;
    mt_vec3 *ws = malloc((size_t)n * sizeof *ws);
    float (*u)[3] = malloc((size_t)n * sizeof *u);
    cf_samp *st = malloc((size_t)n * sizeof *st), *sr = malloc((size_t)n * sizeof *sr);
    double *tdir = malloc((size_t)n * sizeof *tdir), *tf = malloc((size_t)n * 3 * sizeof *tf), worst = 0, fm = 0;
    mt_rng rng;
    char q[160], ex[200], got[200];
    if (!ws || !u || !st || !sr || !tdir || !tf) {
        r = -2;
        goto out;
    }
    mt_rng_seed(&rng, seed_of(c->name, 7), 9);
    for (i = 0; i < n; ++i) {
        ws[i] = wo[i / NSTRATA];
        u[i][0] = (float)(((i % NSTRATA) + 0.5) / NSTRATA);
        u[i][1] = u[i][2] = 0.5f;
    }
    if (cf_impl_sample(test, n, ws, (const float(*)[3])u, st)) {
        r = -1;
        goto out;
    }
    cf_impl_sample(ref, n, ws, (const float(*)[3])u, sr);
    for (i = 0; i < n; ++i)
        for (k = 0; k < 3; ++k) fm = fmax(fm, sr[i].f[k]);
    /* materia's conditioning: its delta sample under perturbed wo */
    for (i = 0; i < n; ++i) {
        double d = 0, sf[3] = {0, 0, 0};
        int p;
        if (!(sr[i].flags & MT_BSDF_SPECULAR) || !(sr[i].pdf > 0)) continue;
        for (p = 0; p < 4; ++p) {
            mt_bsdf_sample s = mt_bsdf_sample_f(ref->bsdf, perturb(ws[i], p), u[i][0], u[i][1], u[i][2], MT_BSDF_ALL);
            if (!(s.pdf > 0) || !(s.type & MT_BSDF_SPECULAR)) continue;
            d = fmax(d, sqrt((s.wi.x - sr[i].wi[0]) * (s.wi.x - sr[i].wi[0]) + (s.wi.y - sr[i].wi[1]) * (s.wi.y - sr[i].wi[1]) +
                             (s.wi.z - sr[i].wi[2]) * (s.wi.z - sr[i].wi[2])));
            for (k = 0; k < 3; ++k) sf[k] = fmax(sf[k], fabs(s.f.c[k] - sr[i].f[k]));
        }
        tdir[i] = 4 * d + 1e-5;
        for (k = 0; k < 3; ++k) tf[3 * i + k] = bound(sr[i].f[k], sf[k], 64 * EPSF, fm);
    }
    /* each test delta sample against materia's of the same wo */
    for (i = 0; i < n; ++i) {
        double best = 1e300;
        int w = i / NSTRATA;
        if (!is_delta(st + i)) continue;
        tested++;
        for (j = w * NSTRATA; j < (w + 1) * NSTRATA; ++j)
            if (is_delta(sr + j)) best = fmin(best, delta_err(st + i, sr + j, tdir[j], tf + 3 * j));
        if (best > 1) {
            bad++;
            q_sample(q, sizeof q, ws[i], u[i]);
            a_sample(got, sizeof got, st + i);
            snprintf(ex, sizeof ex, "one of materia's delta lobes (direction and f)");
            cf_worst_add(res[CK_AGREE_DELTA].worst, best, q, ex, got);
        }
        if (best < 1e299) worst = fmax(worst, best);
        else worst = 1e30;
    }
    /* materia's lobes that the test never produced */
    for (j = 0; j < n; ++j) {
        int w = j / NSTRATA, found = 0;
        double wsum = 0, wj;
        if (!is_delta(sr + j)) continue;
        for (i = w * NSTRATA; i < (w + 1) * NSTRATA; ++i)
            if (sr[i].pdf > 0) wsum += sr[i].f[0] + sr[i].f[1] + sr[i].f[2];
        wj = sr[j].f[0] + sr[j].f[1] + sr[j].f[2];
        if (wj < wsum / 16) continue;
        for (i = w * NSTRATA; i < (w + 1) * NSTRATA && !found; ++i)
            found = is_delta(st + i) && delta_err(st + i, sr + j, tdir[j], tf + 3 * j) <= 1;
        if (!found) {
            bad++;
            q_sample(q, sizeof q, ws[j], u[j]);
            a_sample(ex, sizeof ex, sr + j);
            cf_worst_add(res[CK_AGREE_DELTA].worst, 1e3, q, ex, "never produced by the implementation at this wo");
        }
    }
    set(&res[CK_AGREE_DELTA], bad == 0, "err/tol <= 1", "worst err/tol %.3g over %d delta samples, %d off", worst,
        tested, bad);
out:
    free(ws);
    free(u);
    free(st);
    free(sr);
    free(tdir);
    free(tf);
    return r;
}

/* helmholtz: specular transmission there and back, from the test alone. */
static int helmholtz_check(const cf_impl_config *c, cf_impl *test, double eta, const mt_vec3 *wo0, int nwo0,
                           cf_impl_result *res)
{
    enum { NW = 24, NU = 8 };
    mt_vec3 wo[NW + MAXWO], ws[(NW + MAXWO) * NU];
    float u[(NW + MAXWO) * NU][3];
    cf_samp s1[(NW + MAXWO) * NU], s2[(NW + MAXWO) * NU];
    int nwo = 0, i, j, n, pairs = 0, r = 0, t1[NW + MAXWO];
    double worst[2] = {0, 0}, worst_dir = 0;
    mt_rng rng;
    char q[160], ex[160], got[160];
    cf_worst wl[2][CI_WORST];
    memset(wl, 0, sizeof wl);
    mt_rng_seed(&rng, seed_of(c->name, 3), 11);
    for (i = 0; i < nwo0; ++i) wo[nwo++] = wo0[i];
    while (nwo < NW + MAXWO) wo[nwo++] = fl(mt_uniform_sample_sphere(mt_rng_uniform(&rng), mt_rng_uniform(&rng)));
    n = nwo * NU;
    for (i = 0; i < n; ++i) {
        ws[i] = wo[i / NU];
        u[i][0] = (float)(((i % NU) + 0.5) / NU);
        u[i][1] = u[i][2] = 0.5f;
    }
    if (cf_impl_sample(test, n, ws, (const float(*)[3])u, s1)) return -1;
    /* the first transmission of each wo, and from where it went */
    for (i = 0; i < nwo; ++i) {
        t1[i] = -1;
        for (j = 0; j < NU; ++j) {
            const cf_samp *x = s1 + i * NU + j;
            if ((x->flags & (MT_BSDF_TRANSMISSION | MT_BSDF_SPECULAR)) == (MT_BSDF_TRANSMISSION | MT_BSDF_SPECULAR) &&
                x->pdf > 0 && isfinite(x->wi[0]) && isfinite(x->wi[1]) && isfinite(x->wi[2])) {
                t1[i] = i * NU + j;
                break;
            }
        }
        for (j = 0; j < NU; ++j) ws[i * NU + j] = t1[i] >= 0 ? fl3(s1[t1[i]].wi) : wo[i];
    }
    if (cf_impl_sample(test, n, ws, (const float(*)[3])u, s2)) return -1;
    for (i = 0; i < nwo; ++i) {
        const cf_samp *a = t1[i] >= 0 ? s1 + t1[i] : NULL, *b = NULL;
        double cmin, tol, w1, w2, eo, ei, d, e[2];
        int form;
        if (!a) continue;
        for (j = 0; j < NU && !b; ++j) {
            const cf_samp *x = s2 + i * NU + j;
            if ((x->flags & (MT_BSDF_TRANSMISSION | MT_BSDF_SPECULAR)) == (MT_BSDF_TRANSMISSION | MT_BSDF_SPECULAR) &&
                x->pdf > 0)
                b = x;
        }
        if (!b) continue;
        pairs++;
        cmin = fmin(fabs(wo[i].z), fabs(a->wi[2]));
        tol = 64 * EPSF * fmax(eta * eta, 1 / (eta * eta)) / fmax(cmin * cmin, 1e-12);
        d = sqrt((b->wi[0] - wo[i].x) * (b->wi[0] - wo[i].x) + (b->wi[1] - wo[i].y) * (b->wi[1] - wo[i].y) +
                 (b->wi[2] - wo[i].z) * (b->wi[2] - wo[i].z)) /
            tol;
        if (!isfinite(d)) d = 1e30;
        worst_dir = fmax(worst_dir, d);
        w1 = a->f[0] * fabs(a->wi[2]) / a->pdf;
        w2 = b->f[0] * fabs(wo[i].z) / b->pdf;
        eo = wo[i].z > 0 ? 1 : eta;
        ei = wo[i].z > 0 ? eta : 1;
        e[0] = rel(w1, w2) / tol;
        e[1] = rel(w1 * (ei / eo) * (ei / eo), w2 * (eo / ei) * (eo / ei)) / tol;
        for (form = 0; form < 2; ++form) {
            if (!isfinite(e[form])) e[form] = 1e30;
            worst[form] = fmax(worst[form], fmax(e[form], d));
            if (e[form] > 1 || d > 1) {
                q_sample(q, sizeof q, wo[i], u[t1[i]]);
                snprintf(ex, sizeof ex, "%s, the way back to wo", form ? "w(o->i) (ei/eo)^2 = w(i->o) (eo/ei)^2" : "w(o->i) = w(i->o)");
                snprintf(got, sizeof got, "w(o->i) %.9g, w(i->o) %.9g, back at %.9g %.9g %.9g", w1, w2, b->wi[0], b->wi[1],
                         b->wi[2]);
                cf_worst_add(wl[form], fmax(e[form], d), q, ex, got);
            }
        }
    }
    {
        int form = worst[0] <= worst[1] ? 0 : 1;
        memcpy(res[CK_HELMHOLTZ].worst, wl[form], sizeof wl[form]);
        set(&res[CK_HELMHOLTZ], pairs > 0 && worst[form] <= 1, "<= 1 (64 eps cond.)",
            "err/tol %.3g in the %s form (other %.3g), |T(T(w)) - w| %.2g, %d pairs", worst[form],
            form ? "radiance" : "pbrt-v2", worst[1 - form], worst_dir, pairs);
    }
    return r;
}

/* extremes: every answer on the grid finite and non-negative. */
static int extremes_check(cf_impl *test, cf_impl_result *res)
{
    static const float us[5] = {0, 0.25f, 0.5f, 0.999999f, 0.99999994f};
    mt_vec3 d[64], *a, *b;
    int nd = cf_extreme_directions(d, 64), i, j, k, n = 0, ns = 0, r = 0;
    long bad = 0;
    cf_eval *e;
    cf_samp *s;
    float (*u)[3];
    char q[160], got[200];
    for (i = 0; i < nd; ++i) d[i] = fl(d[i]);
    a = malloc((size_t)nd * (nd > 125 ? nd : 125) * sizeof *a);
    b = malloc((size_t)nd * nd * sizeof *b);
    e = malloc((size_t)nd * nd * sizeof *e);
    s = malloc((size_t)nd * 125 * sizeof *s);
    u = malloc((size_t)nd * 125 * sizeof *u);
    if (!a || !b || !e || !s || !u) {
        r = -2;
        goto out;
    }
    for (i = 0; i < nd; ++i)
        for (j = 0; j < nd; ++j) {
            a[n] = d[i];
            b[n++] = d[j];
        }
    if (cf_impl_eval(test, n, a, b, e)) {
        r = -1;
        goto out;
    }
    for (i = 0; i < n; ++i) {
        int ok = finite_nonneg(e[i].pdf);
        for (k = 0; k < 3; ++k) ok &= finite_nonneg(e[i].f[k]);
        if (!ok) {
            bad++;
            q_eval(q, sizeof q, a[i], b[i]);
            a_eval(got, sizeof got, e + i);
            cf_worst_add(res[CK_EXTREMES].worst, 1, q, "finite, >= 0", got);
        }
    }
    for (i = 0; i < nd; ++i)
        for (j = 0; j < 125; ++j) {
            a[ns] = d[i];
            u[ns][0] = us[j / 25];
            u[ns][1] = us[(j / 5) % 5];
            u[ns++][2] = us[j % 5];
        }
    if (cf_impl_sample(test, ns, a, (const float(*)[3])u, s)) {
        r = -1;
        goto out;
    }
    for (i = 0; i < ns; ++i) {
        if (!sample_valid(s + i, 1e-4)) {
            bad++;
            q_sample(q, sizeof q, a[i], u[i]);
            a_sample(got, sizeof got, s + i);
            cf_worst_add(res[CK_EXTREMES].worst, 1, q, "finite, >= 0, |wi| = 1", got);
        }
    }
    set(&res[CK_EXTREMES], bad == 0, "0 violations", "%ld violations in %d evals and %d samples", bad, n, ns);
out:
    free(a);
    free(b);
    free(e);
    free(s);
    free(u);
    return r;
}

int cf_impl_checks(const cf_impl_run *run, const cf_impl_config *c, cf_impl *test, cf_impl *ref,
                   cf_impl_result res[CK_NCHECK])
{
    mt_vec3 wo[MAXWO];
    int nwo = wo_set(c, run->nwo_max, wo), w, k, r = 0;
    int density = has_kind(ref->bsdf, 0, MT_BSDF_SPECULAR), delta = has_kind(ref->bsdf, MT_BSDF_SPECULAR, 0);
    acc a;
    const cf_config *cfg = &run->cfg;
    char b[64];
    for (k = 0; k < CK_NCHECK; ++k) {
        memset(&res[k], 0, sizeof res[k]);
        res[k].ok = -1;
    }
    memset(&a, 0, sizeof a);
    a.chi[0].min_p = a.chi[1].min_p = 2;
    a.rho_lo = 1e300;
    a.rho_hi = -1e300;
    for (w = 0; w < nwo && !r; ++w) r = sampling_wo(run, c, test, ref, wo[w], w, density, &a, res);
    if (r) return r;
    {
        double id_tol = fmax(1e-3, noise_allowance(c));
        snprintf(b, sizeof b, "rel <= %.2g", id_tol);
        set(&res[CK_IDENTITY], a.id_bad == 0, b, "max rel %.2g over %ld samples, %ld invalid", a.id_worst, a.id_tested,
            a.id_bad);
    }
    if (density) {
        snprintf(b, sizeof b, "p >= %.2g", cfg->alpha_test);
        for (k = 0; k < 2; ++k)
            if (a.chi[k].hard)
                set(&res[k ? CK_CHI2_MATERIA : CK_CHI2], 0, b, "hard failure: samples where %s pdf is 0",
                    k ? "materia's" : "its own");
            else
                set(&res[k ? CK_CHI2_MATERIA : CK_CHI2], a.chi[k].min_p >= cfg->alpha_test, b, "min p %.3g (%ld dof)",
                    a.chi[k].min_p, a.chi[k].dof);
        set(&res[CK_INTEGRAL], a.worst_int <= 1, "dev/tol <= 1", "dev/tol %.2f (%s)", a.worst_int, a.int_what);
        if (a.gap_bad)
            set(&res[CK_FURNACE_MC], 0, "pdf covers f", "%s", a.gap_what);
        else
            set(&res[CK_FURNACE_MC], a.worst_mc <= 1, "dev/tol <= 1", "dev/tol %.2f (%s)", a.worst_mc, a.mc_what);
    }
    if (c->flags & CI_FURNACE_LE1)
        set(&res[CK_FURNACE], a.worst_excess <= 0, "rho <= 1 (+noise)", "rho %.6f..%.6f (%s)", a.rho_lo, a.rho_hi,
            a.rho_what);
    if ((r = pair_checks(c, test, ref, wo, nwo, density, res))) return r;
    if (delta && (r = delta_check(c, test, ref, wo, nwo, res))) return r;
    if (has_kind(ref->bsdf, MT_BSDF_TRANSMISSION | MT_BSDF_SPECULAR, 0) &&
        (r = helmholtz_check(c, test, mt_bsdf_eta(ref->bsdf), wo, nwo, res)))
        return r;
    return extremes_check(test, res);
}
