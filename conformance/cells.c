/*
 * The cells of the chi-square (cf_layout), and the cubature of an
 * implementation's eval over them.
 *
 * Cells are laid where a pilot sample of the implementation's own sampler
 * fell: rows of cos theta with equal counts of pilot directions (the
 * horizon always a row boundary, the rows of each hemisphere in proportion
 * to its pilot count), and in each row columns of phi with equal counts. A
 * lobe of roughness 0.001 that a fixed grid of the sphere puts into one
 * cell is spread over hundreds. The pilot is drawn apart from the samples
 * that are tested (another stream of random numbers), so the cells are
 * fixed before those samples and their expected counts, the cubature of
 * the implementation's pdf over each cell, are what the chi-square tests
 * them against: the layout decides the test's power, not its validity.
 *
 * The cubature asks for one value at a time; a child answers best in big
 * batches. So each cell's cubature runs on a cache of answers: a node not
 * in it is recorded and counts as 0, and the cell is done once a run
 * needed no such node. The missing nodes of every cell are then asked in
 * one batch and the unfinished cells run again; the last run of each cell
 * is exactly the cubature of the implementation's own values. An
 * implementation in this process answers at once and needs no rounds: the
 * values, and so the integrals, are the same.
 */
#include <stdlib.h>
#include <string.h>
#include "pass.h"

#define TWO_PI 6.283185307179586476925
/* pilot directions per column at least: fewer make a quantile a guess */
#define PILOT_PER_COLUMN 4

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double phi_of(double x, double y)
{
    double p = atan2(y, x);
    if (p < 0) p += TWO_PI;
    return p >= TWO_PI ? 0 : p;
}

/* k - 1 boundaries at the quantiles of the m sorted values v (midpoints of
 * neighbours), strictly inside (lo, hi) and increasing: written to b, the
 * count returned. */
static int quantiles(const double *v, long m, int k, double lo, double hi, double *b)
{
    int j, nb = 0;
    for (j = 1; j < k; ++j) {
        long i = (long)((double)j * (double)m / k);
        double x;
        if (i < 1 || i >= m) continue;
        x = 0.5 * (v[i - 1] + v[i]);
        if (!(x > lo && x < hi) || (nb && !(x > b[nb - 1]))) continue;
        b[nb++] = x;
    }
    return nb;
}

void cf_layout_free(cf_layout *l)
{
    free(l->z);
    free(l->first);
    free(l->phi);
    memset(l, 0, sizeof *l);
}

int cf_layout_copy(cf_layout *dst, const cf_layout *src)
{
    memset(dst, 0, sizeof *dst);
    if (!src->ncell) return 0;
    dst->z = malloc((size_t)(src->nrow + 1) * sizeof *dst->z);
    dst->first = malloc((size_t)(src->nrow + 1) * sizeof *dst->first);
    dst->phi = malloc((size_t)src->ncell * sizeof *dst->phi);
    if (!dst->z || !dst->first || !dst->phi) {
        cf_layout_free(dst);
        return -1;
    }
    dst->nrow = src->nrow;
    dst->ncell = src->ncell;
    memcpy(dst->z, src->z, (size_t)(src->nrow + 1) * sizeof *dst->z);
    memcpy(dst->first, src->first, (size_t)(src->nrow + 1) * sizeof *dst->first);
    memcpy(dst->phi, src->phi, (size_t)src->ncell * sizeof *dst->phi);
    return 0;
}

int cf_layout_from(cf_layout *l, const cf_v3 *pilot, long m, int nphi, int nz)
{
    long up = 0, i, k;
    int rup, rdn, nrow = 0, r, h;
    double *zs = malloc((size_t)(m > 0 ? m : 1) * sizeof *zs), *ps = malloc((size_t)(m > 0 ? m : 1) * sizeof *ps);
    double *zb = malloc((size_t)(nz + 2) * sizeof *zb);
    memset(l, 0, sizeof *l);
    l->first = malloc((size_t)(nz + 2) * sizeof *l->first);
    l->phi = malloc((size_t)(nz + 1) * (size_t)nphi * sizeof *l->phi);
    if (!zs || !ps || !zb || !l->first || !l->phi) goto oom;
    for (i = 0; i < m; ++i) up += pilot[i].z > 0;
    /* rows per hemisphere in proportion to its pilot count, one at least;
     * with no pilot at all, equal-area rows */
    if (m == 0) {
        rup = nz / 2 + (nz & 1);
        rdn = nz - rup;
    } else {
        rup = (int)floor((double)nz * (double)up / (double)m + 0.5);
        if (rup < 1) rup = 1;
        if (rup > nz - 1) rup = nz - 1;
        rdn = nz - rup;
    }
    if (rdn < 1) rdn = 1;
    /* the row boundaries, from -1 up */
    zb[nrow++] = -1;
    for (h = 0; h < 2; ++h) {
        long c = 0;
        int rows = h ? rup : rdn, nb;
        double lo = h ? 0 : -1, hi = h ? 1 : 0;
        for (i = 0; i < m; ++i)
            if ((pilot[i].z > 0) == h) zs[c++] = pilot[i].z;
        if (c) {
            qsort(zs, (size_t)c, sizeof *zs, cmp_double);
            nb = quantiles(zs, c, rows, lo, hi, zb + nrow);
        } else {
            for (nb = 0; nb < rows - 1; ++nb) zb[nrow + nb] = lo + (hi - lo) * (nb + 1) / rows;
            if (m) nb = 0; /* a hemisphere the pilot never reached: one row */
        }
        nrow += nb;
        zb[nrow++] = h ? 1 : 0;
    }
    nrow--; /* zb[0..nrow] are the boundaries */
    l->nrow = nrow;
    l->z = zb;
    zb = NULL;
    /* columns of each row at the quantiles of its pilot's phi */
    for (r = 0; r < nrow; ++r) {
        long c = 0;
        int cols, nb;
        for (i = 0; i < m; ++i)
            if (pilot[i].z >= l->z[r] && (pilot[i].z < l->z[r + 1] || (r == nrow - 1 && pilot[i].z <= 1)))
                ps[c++] = phi_of(pilot[i].x, pilot[i].y);
        cols = m == 0 ? nphi : (int)(c / PILOT_PER_COLUMN);
        if (cols > nphi) cols = nphi;
        if (cols < 1) cols = 1;
        l->first[r] = l->ncell;
        l->phi[l->ncell++] = 0;
        if (m == 0) {
            for (k = 1; k < cols; ++k) l->phi[l->ncell++] = TWO_PI * (double)k / cols;
            continue;
        }
        qsort(ps, (size_t)c, sizeof *ps, cmp_double);
        nb = quantiles(ps, c, cols, 0, TWO_PI, l->phi + l->ncell);
        l->ncell += nb;
    }
    l->first[nrow] = l->ncell;
    free(zs);
    free(ps);
    return 0;
oom:
    free(zs);
    free(ps);
    free(zb);
    cf_layout_free(l);
    return -1;
}

int cf_layout_cell(const cf_layout *l, double x, double y, double z)
{
    int lo = 0, hi = l->nrow - 1, r, a, b;
    double p;
    while (lo < hi) { /* the last row whose lower boundary is <= z */
        int mid = (lo + hi + 1) / 2;
        if (l->z[mid] <= z)
            lo = mid;
        else
            hi = mid - 1;
    }
    r = lo;
    p = phi_of(x, y);
    a = l->first[r];
    b = l->first[r + 1] - 1;
    while (a < b) {
        int mid = (a + b + 1) / 2;
        if (l->phi[mid] <= p)
            a = mid;
        else
            b = mid - 1;
    }
    return a;
}

int cf_layout_row(const cf_layout *l, int c)
{
    int lo = 0, hi = l->nrow - 1;
    while (lo < hi) {
        int mid = (lo + hi + 1) / 2;
        if (l->first[mid] <= c)
            lo = mid;
        else
            hi = mid - 1;
    }
    return lo;
}

void cf_layout_bounds(const cf_layout *l, int c, double *p0, double *p1, double *z0, double *z1)
{
    int lo = cf_layout_row(l, c);
    *z0 = l->z[lo];
    *z1 = l->z[lo + 1];
    *p0 = l->phi[c];
    *p1 = c + 1 < l->first[lo + 1] ? l->phi[c + 1] : TWO_PI;
}

/* ---- a cache of an implementation's answers, keyed by direction --------- */
typedef struct cache {
    double *key; /* 3 per slot */
    double *val; /* 4 per slot: f rgb, pdf */
    unsigned char *state; /* 0 empty, 1 asked, 2 answered */
    size_t cap, n;
    cf_v3 *miss;
    size_t nmiss, cap_miss;
} cache;

static size_t hash3(const double *k)
{
    uint64_t b[3], h;
    memcpy(b, k, sizeof b);
    /* splitmix64's finalizer: every key bit reaches the low bits */
    h = b[0] ^ (b[1] * 0x9e3779b97f4a7c15ULL) ^ (b[2] * 0xc2b2ae3d27d4eb4fULL);
    h = (h ^ (h >> 30)) * 0xbf58476d1ce4e5b9ULL;
    h = (h ^ (h >> 27)) * 0x94d049bb133111ebULL;
    return (size_t)(h ^ (h >> 31));
}

static size_t find_slot(const cache *c, const double *k)
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
    n.cap = c->cap ? 2 * c->cap : 1 << 14;
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

static void cache_free(cache *c)
{
    free(c->key);
    free(c->val);
    free(c->state);
    free(c->miss);
    memset(c, 0, sizeof *c);
}

/* The value at d: 1 and v (f rgb, pdf) when answered; 0 (recorded as
 * missing) when not yet; -1 out of memory. */
static int cache_get(cache *c, cf_v3 d, double *v)
{
    double k[3];
    size_t h;
    k[0] = d.x;
    k[1] = d.y;
    k[2] = d.z;
    if (2 * (c->n + 1) > c->cap && cache_grow(c)) return -1;
    h = find_slot(c, k);
    if (c->state[h] == 2) {
        memcpy(v, c->val + 4 * h, 4 * sizeof *v);
        return 1;
    }
    if (c->state[h] == 1) return 0;
    if (c->nmiss == c->cap_miss) {
        size_t nc = c->cap_miss ? 2 * c->cap_miss : 4096;
        cf_v3 *m = realloc(c->miss, nc * sizeof *m);
        if (!m) return -1;
        c->miss = m;
        c->cap_miss = nc;
    }
    memcpy(c->key + 3 * h, k, sizeof k);
    c->state[h] = 1;
    c->n++;
    c->miss[c->nmiss++] = d;
    return 0;
}

/* Asks the implementation every missing value: eval(wo, d) (or eval(d, wo)
 * when reverse). */
static int cache_fill(cache *c, cf_impl *im, cf_v3 wo, int reverse)
{
    cf_v3 *a;
    cf_eval *e;
    size_t i;
    int r;
    if (!c->nmiss) return 0;
    a = malloc(c->nmiss * sizeof *a);
    e = malloc(c->nmiss * sizeof *e);
    if (!a || !e) {
        free(a);
        free(e);
        return CF_NOMEM;
    }
    for (i = 0; i < c->nmiss; ++i) a[i] = wo;
    r = reverse ? im->ops->eval(im, (int)c->nmiss, c->miss, a, e) : im->ops->eval(im, (int)c->nmiss, a, c->miss, e);
    for (i = 0; !r && i < c->nmiss; ++i) {
        double k[3], *v;
        int j;
        k[0] = c->miss[i].x;
        k[1] = c->miss[i].y;
        k[2] = c->miss[i].z;
        v = c->val + 4 * find_slot(c, k);
        for (j = 0; j < 3; ++j) v[j] = isfinite(e[i].f[j]) ? e[i].f[j] : 0;
        v[3] = isfinite(e[i].pdf) ? e[i].pdf : 0;
        c->state[find_slot(c, k)] = 2;
    }
    c->nmiss = 0;
    free(a);
    free(e);
    return r;
}

/* ---- the integrand ------------------------------------------------------------ */
typedef struct integ {
    cf_impl *im;
    cf_v3 wo, ns, ng;
    int other;       /* 0: forward (7 values); 1: the other side, both ways (6 values) */
    cache fwd, rev;
    int missing, oom, failed;
} integ;

/* f and pdf at (wo, d), or at (d, wo) when reverse: 1 when known. */
static int value(integ *g, cf_v3 d, int reverse, double *v)
{
    int r;
    if (g->im->direct) {
        cf_eval e;
        int k, st = reverse ? g->im->ops->eval(g->im, 1, &d, &g->wo, &e) : g->im->ops->eval(g->im, 1, &g->wo, &d, &e);
        if (st) {
            g->failed = st;
            return 0;
        }
        for (k = 0; k < 3; ++k) v[k] = isfinite(e.f[k]) ? e.f[k] : 0;
        v[3] = isfinite(e.pdf) ? e.pdf : 0;
        return 1;
    }
    r = cache_get(reverse ? &g->rev : &g->fwd, d, v);
    if (r < 0) g->oom = 1;
    if (r == 0) g->missing = 1;
    return r == 1;
}

static void integrand(void *ctx, double phi, double z, double *out)
{
    integ *g = ctx;
    double s = sqrt(fmax(0, 1 - z * z));
    cf_v3 d = cf_v3_float(cf_v3_make(s * cos(phi), s * sin(phi), z));
    double c = fabs(d.x * g->ns.x + d.y * g->ns.y + d.z * g->ns.z), v[4], w[4];
    int k;
    for (k = 0; k < 7; ++k) out[k] = 0;
    if (!g->other) {
        if (!value(g, d, 0, v)) return;
        out[0] = v[3];
        for (k = 0; k < 3; ++k) {
            out[1 + k] = v[k] * c;
            out[4 + k] = v[3] > 0 ? 0 : v[k] * c; /* energy no sample can reach */
        }
        return;
    }
    /* across the surface only: f(wo, d) |cos| and f(d, wo) |cos| */
    if ((d.x * g->ng.x + d.y * g->ng.y + d.z * g->ng.z) * (g->wo.x * g->ng.x + g->wo.y * g->ng.y + g->wo.z * g->ng.z) >= 0)
        return;
    if (!value(g, d, 0, v) || !value(g, d, 1, w)) return;
    for (k = 0; k < 3; ++k) {
        out[k] = v[k] * c;
        out[3 + k] = w[k] * c;
    }
}

/* ---- where in a cell the cubature starts ----------------------------------
 * A cell laid by the pilot can be wide where the pilot was sparse and still
 * hold the tail of a sharp lobe along its edge: a cubature whose first
 * nodes all miss it sees nothing there and says it converged (measured: the
 * cells next to a Blinn lobe of exponent 10^4 at cos theta 0.3 lost 1.1% of
 * the pdf's integral this way, with error estimates of 1e-9). So each cell
 * is first cut into regions:
 *  - towards an edge it shares with a cell (or row) more than GRADE_RATIO
 *    times narrower, at distances w, 4 w, 16 w, ... from it (w the
 *    neighbour's width): where a lobe's tail crosses the edge, it decays
 *    over a few w, and there the regions are that narrow;
 *  - around its pilot samples, when the middle 80% of them
 *    occupy less than a quarter of its extent along an axis (with a margin
 *    of a quarter of their spread);
 * and each region starts from a grid as fine as its share of the pilot
 * asks (mt_cubature_grid). The integral is the same; only the nodes that
 * find it are placed better. */
#define GRADE_RATIO 4
#define GRADE_FACTOR 4
#define SPLIT_MIN_POINTS 8
#define SPLIT_FRACTION 0.25
#define SPLIT_QUANTILE 0.1
#define MAX_CUTS 40

/* Cuts from the edge at e towards the middle of a cell of width W (dir +1
 * from its lower edge, -1 from its upper), whose neighbour there is w wide. */
static int grade(double *cut, int n, double e, double W, double w, int dir)
{
    double x;
    if (!(w > 0) || W <= GRADE_RATIO * w) return n;
    for (x = w; x < 0.5 * W && n < MAX_CUTS; x *= GRADE_FACTOR) cut[n++] = e + dir * x;
    return n;
}

/* Sorts the cuts, keeps those strictly inside (lo, hi) once, and adds the
 * ends: the count of boundaries. */
static int bounds_of(double *cut, int n, double lo, double hi)
{
    int i, m = 0;
    qsort(cut, (size_t)n, sizeof *cut, cmp_double);
    for (i = 0; i < n; ++i)
        if (cut[i] > lo && cut[i] < hi && (!m || cut[i] > cut[m - 1])) cut[m++] = cut[i];
    memmove(cut + 1, cut, (size_t)m * sizeof *cut);
    cut[0] = lo;
    cut[m + 1] = hi;
    return m + 2;
}

/* the region of x among the n + 1 sorted boundaries b (n regions) */
static int region_of(const double *b, int n, double x)
{
    int lo = 0, hi = n - 1;
    while (lo < hi) {
        int mid = (lo + hi + 1) / 2;
        if (b[mid] <= x)
            lo = mid;
        else
            hi = mid - 1;
    }
    return lo;
}

int cf_regions_build(cf_regions *g, const cf_layout *l, const cf_v3 *pts, long total)
{
    long i, *start = NULL, *order = NULL, *fill = NULL, *inreg = NULL;
    double *ph = NULL, *zz = NULL, *pphi = NULL;
    int *pcell = NULL, c, cap = 0, r, status = CF_NOMEM;
    size_t sz = (size_t)(total > 0 ? total : 1);
    memset(g, 0, sizeof *g);
    g->first = malloc((size_t)(l->ncell + 1) * sizeof *g->first);
    start = calloc((size_t)l->ncell + 1, sizeof *start);
    fill = calloc((size_t)l->ncell + 1, sizeof *fill);
    order = malloc(sz * sizeof *order);
    ph = malloc(sz * sizeof *ph);
    zz = malloc(sz * sizeof *zz);
    pphi = malloc(sz * sizeof *pphi);
    pcell = malloc(sz * sizeof *pcell);
    inreg = malloc((size_t)(MAX_CUTS + 2) * (MAX_CUTS + 2) * sizeof *inreg);
    if (!g->first || !start || !fill || !order || !ph || !zz || !pphi || !pcell || !inreg) goto oom;
    /* each point's cell and azimuth once; the points of each cell by a
     * counting sort */
    for (i = 0; i < total; ++i) {
        double f = atan2(pts[i].y, pts[i].x);
        pphi[i] = f < 0 ? f + TWO_PI : f;
        pcell[i] = cf_layout_cell(l, pts[i].x, pts[i].y, pts[i].z);
        start[pcell[i] + 1]++;
    }
    for (c = 0; c < l->ncell; ++c) start[c + 1] += start[c];
    for (i = 0; i < total; ++i) order[start[pcell[i]] + fill[pcell[i]]++] = i;
    for (r = 0; r < l->nrow; ++r)
        for (c = l->first[r]; c < l->first[r + 1]; ++c) {
            double p0, p1, z0, z1, cp[MAX_CUTS + 2], cz[MAX_CUTS + 2], q0, q1, y0, y1;
            long m = start[c + 1] - start[c], k;
            int np = 0, nz = 0, u, v, lo = l->first[r], hi = l->first[r + 1] - 1;
            cf_layout_bounds(l, c, &p0, &p1, &z0, &z1);
            /* towards narrower neighbours: in phi within the row (it wraps
             * at 2 pi), in z the rows below and above */
            if (hi > lo) {
                int left = c > lo ? c - 1 : hi, right = c < hi ? c + 1 : lo;
                cf_layout_bounds(l, left, &q0, &q1, &y0, &y1);
                np = grade(cp, np, p0, p1 - p0, q1 - q0, 1);
                cf_layout_bounds(l, right, &q0, &q1, &y0, &y1);
                np = grade(cp, np, p1, p1 - p0, q1 - q0, -1);
            }
            if (r > 0) nz = grade(cz, nz, z0, z1 - z0, l->z[r] - l->z[r - 1], 1);
            if (r < l->nrow - 1) nz = grade(cz, nz, z1, z1 - z0, l->z[r + 2] - l->z[r + 1], -1);
            /* around its samples */
            for (k = 0; k < m; ++k) {
                long j = order[start[c] + k];
                ph[k] = pphi[j];
                zz[k] = pts[j].z;
            }
            if (m >= SPLIT_MIN_POINTS) {
                int axis;
                double *sp = malloc((size_t)m * 2 * sizeof *sp);
                if (!sp) goto oom;
                memcpy(sp, ph, (size_t)m * sizeof *sp);
                memcpy(sp + m, zz, (size_t)m * sizeof *sp);
                qsort(sp, (size_t)m, sizeof *sp, cmp_double);
                qsort(sp + m, (size_t)m, sizeof *sp, cmp_double);
                for (axis = 0; axis < 2; ++axis) {
                    const double *v0 = sp + (axis ? m : 0);
                    double e0 = axis ? z0 : p0, e1 = axis ? z1 : p1, *cut = axis ? cz : cp;
                    double qa = v0[(long)(SPLIT_QUANTILE * (double)(m - 1))];
                    double qb = v0[(long)((1 - SPLIT_QUANTILE) * (double)(m - 1))];
                    double mg = SPLIT_FRACTION * (qb - qa) + 1e-12 * (e1 - e0);
                    int *nc = axis ? &nz : &np;
                    if (qb - qa >= SPLIT_FRACTION * (e1 - e0) || *nc > MAX_CUTS - 2) continue;
                    cut[(*nc)++] = qa - mg;
                    cut[(*nc)++] = qb + mg;
                }
                free(sp);
            }
            np = bounds_of(cp, np, p0, p1);
            nz = bounds_of(cz, nz, z0, z1);
            /* the points of each region */
            for (u = 0; u < (np - 1) * (nz - 1); ++u) inreg[u] = 0;
            for (k = 0; k < m; ++k) inreg[region_of(cp, np - 1, ph[k]) * (nz - 1) + region_of(cz, nz - 1, zz[k])]++;
            g->first[c] = g->n;
            for (u = 0; u + 1 < np; ++u)
                for (v = 0; v + 1 < nz; ++v) {
                    if (g->n == cap) {
                        int ncap = cap ? 2 * cap : 1024;
                        double(*rr)[5] = realloc(g->rect, (size_t)ncap * sizeof *rr);
                        if (!rr) goto oom;
                        g->rect = rr;
                        cap = ncap;
                    }
                    g->rect[g->n][0] = cp[u];
                    g->rect[g->n][1] = cp[u + 1];
                    g->rect[g->n][2] = cz[v];
                    g->rect[g->n][3] = cz[v + 1];
                    /* its start grid: its share of the points against the average cell's */
                    g->rect[g->n++][4] = mt_cubature_grid((double)inreg[u * (nz - 1) + v] * l->ncell /
                                                          (double)(total > 0 ? total : 1));
                }
        }
    g->first[l->ncell] = g->n;
    status = 0;
oom:
    free(start);
    free(fill);
    free(order);
    free(ph);
    free(zz);
    free(pphi);
    free(pcell);
    free(inreg);
    if (status) cf_regions_free(g);
    return status;
}

void cf_regions_free(cf_regions *g)
{
    free(g->first);
    free(g->rect);
    memset(g, 0, sizeof *g);
}

/* The integral over cell c (7 values) and its error estimates: the sum
 * over its regions. */
static int cell_cubature(mt_cubature_fn fn, void *ctx, int ncomp, const cf_regions *g, int c, double abs_tol,
                         double *out, double *err)
{
    int k, j, nr = g->first[c + 1] - g->first[c];
    for (k = 0; k < 7; ++k) out[k] = err[k] = 0;
    for (j = g->first[c]; j < g->first[c + 1]; ++j) {
        const double *r = g->rect[j];
        int sub = (int)r[4];
        mt_cubature_result res;
        mt_error e;
        mt_error_clear(&e);
        if (mt_cubature(fn, ctx, ncomp, r[0], r[1], r[2], r[3], sub, sub, 1e-7, abs_tol / nr, 225L * 8 * sub * sub, &res,
                        &e))
            return CF_NOMEM;
        for (k = 0; k < ncomp; ++k) {
            out[k] += res.value[k];
            err[k] += res.error[k];
        }
    }
    return 0;
}

int cf_cells_integrate(cf_impl *im, const cf_layout *l, const cf_regions *rg, cf_v3 wo, cf_v3 ns, cf_v3 ng, int other,
                       long n, double *cellv, double *total, double *err)
{
    int ncell = l->ncell, c, k, r = 0, nv = other ? 6 : 7;
    unsigned char *done = calloc((size_t)ncell, 1);
    double *cv = malloc((size_t)ncell * 14 * sizeof *cv); /* each cell's values and errors */
    double abs_tol = 0.05 / ((double)(n > 0 ? n : 1) * ncell);
    integ g;
    memset(&g, 0, sizeof g);
    g.im = im;
    g.wo = wo;
    g.ns = ns;
    g.ng = ng;
    g.other = other;
    for (k = 0; k < 7; ++k) total[k] = err[k] = 0;
    if (!done || !cv) {
        free(done);
        free(cv);
        return CF_NOMEM;
    }
    for (;;) {
        int left = 0;
        for (c = 0; c < ncell; ++c) {
            if (done[c]) continue;
            g.missing = 0;
            if ((r = cell_cubature(integrand, &g, 7, rg, c, abs_tol, cv + 14 * c, cv + 14 * c + 7)) || g.oom) {
                r = r ? r : CF_NOMEM;
                goto out;
            }
            if (g.failed) {
                r = g.failed;
                goto out;
            }
            if (g.missing)
                left = 1;
            else
                done[c] = 1;
        }
        if (!left) break;
        if ((r = cache_fill(&g.fwd, im, wo, 0)) || (r = cache_fill(&g.rev, im, wo, 1))) goto out;
    }
    /* summed in the cells' order, whatever order they were done in: the
     * same totals in this process and through a child */
    for (c = 0; c < ncell; ++c) {
        if (cellv) cellv[c] = cv[14 * c];
        for (k = 0; k < nv; ++k) {
            total[k] += cv[14 * c + k];
            err[k] += cv[14 * c + 7 + k];
        }
    }
out:
    free(done);
    free(cv);
    cache_free(&g.fwd);
    cache_free(&g.rev);
    return r;
}

/* The integral of materia's pdf over each cell (in-process: its BSDF). */
typedef struct refint {
    const mt_bsdf *b;
    mt_vec3 wo;
} refint;

static void ref_integrand(void *ctx, double phi, double z, double *out)
{
    const refint *g = ctx;
    double s = sqrt(fmax(0, 1 - z * z));
    cf_v3 d = cf_v3_float(cf_v3_make(s * cos(phi), s * sin(phi), z));
    out[0] = mt_bsdf_pdf(g->b, g->wo, mt_v3((mt_real)d.x, (mt_real)d.y, (mt_real)d.z), MT_BSDF_ALL);
}

int cf_cells_ref_pdf(const mt_bsdf *b, const cf_layout *l, const cf_regions *rg, cf_v3 wo, long n, double *cellv)
{
    int c;
    refint g;
    double abs_tol = 0.05 / ((double)(n > 0 ? n : 1) * l->ncell);
    g.b = b;
    g.wo = mt_v3((mt_real)wo.x, (mt_real)wo.y, (mt_real)wo.z);
    for (c = 0; c < l->ncell; ++c) {
        double v[7], e[7];
        if (cell_cubature(ref_integrand, &g, 1, rg, c, abs_tol, v, e)) return CF_NOMEM;
        cellv[c] = v[0];
    }
    return 0;
}
