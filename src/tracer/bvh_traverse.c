/*
 * BVH queries: closest hit and any hit. Read-only on the geometry, no
 * recursion, no allocation: a fixed stack of (child, entry distance).
 *
 * Per ray the inverse direction, the slab order by direction sign and the
 * triangle test's shear are computed once. A node visit computes the entry
 * and exit distances of all four children with the same operations in four
 * lanes (the loop the compiler turns into SIMD code), visits the nearest
 * child hit and stacks the others, farthest first, with their entry
 * distances, which are checked again when popped. The slab test is robust
 * after Ize, "Robust BVH Ray Traversal", JCGT 2013: exit distances are
 * scaled by 1 + 2 gamma(3), and a NaN from 0 * Inf -- a ray lying in a
 * slab's plane -- is ignored rather than propagated.
 */
#include "tracer/bvh.h"
#include "tracer/triangle.h"

/* The triangle test's set-up (trav's tr, to, ts) is made at a ray's first
 * triangle leaf, under the tri_ready flag, so that rays meeting only
 * quadrics never pay for it. gcc -O3 inlines far enough to see the reads but
 * not the flag, and warns that they may be uninitialized; zeroing them for
 * every ray would cost the stores the flag saves. */
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

/* The float build on x86-64 tests the four boxes of a node with SSE, part
 * of the x86-64 baseline; other builds run the same arithmetic lane by lane
 * (MT_NO_SIMD forces that). */
#if !MT_USE_DOUBLE && defined(__SSE2__) && !defined(MT_NO_SIMD)
#include <emmintrin.h>
#define USE_SSE 1
#else
#define USE_SSE 0
#endif

/* The traversal loop and the tests it calls are inlined into both queries,
 * so that each is compiled for its own case (GCC and clang). */
#if defined(__GNUC__)
#define ALWAYS_INLINE __attribute__((always_inline))
#else
#define ALWAYS_INLINE
#endif

/* Exit distances are scaled by 1 + 2 gamma(3) (Ize), and a node is skipped
 * only when it starts beyond the current closest hit by more than the error
 * of either distance (a few ulps), so that equal or nearly equal hits on box
 * faces -- shared vertices and edges -- are all seen and resolved by id, as
 * a brute-force search resolves them. */
#define EXIT_SCALE (1 + 2 * mt__gamma(3))
#define PRUNE_SCALE (1 + 64 * MT_REAL_EPSILON)

typedef struct trav {
#if USE_SSE
    __m128 vo[3], vi[3], vf[3]; /* origin, inverse direction, its scaled copy */
    __m128 to[3], ts[3];        /* the triangle test's o[kx], o[ky], o[kz] and sx, sy, sz */
#else
    mt_real o[3], inv[3], inv_far[3];
    int nx, ny, nz; /* rows of the near planes: 0/1, 2/3, 4/5 by direction sign */
#endif
    size_t off[6];  /* byte offsets in a node of the near x, y, z and far x, y, z rows */
    const mt_ray *ray;
    int tri_ready;  /* tr (and to, ts) set up: at the first triangle leaf */
    mt__tri_ray tr;
} trav;

#if USE_SSE
/* Lane i of v in all four lanes. */
#define SPLAT(v, i) _mm_shuffle_ps((v), (v), _MM_SHUFFLE(i, i, i, i))

/* The box test's part of the set-up: one division for the three inverse
 * components (the same quotients as three scalar divisions), the near rows
 * from their signs. */
static inline ALWAYS_INLINE void trav_init(trav *t, const mt_ray *r)
{
    __m128 o = _mm_setr_ps(r->o.x, r->o.y, r->o.z, 0);
    __m128 inv = _mm_div_ps(_mm_set1_ps(1), _mm_setr_ps(r->d.x, r->d.y, r->d.z, 1));
    __m128 far = _mm_mul_ps(inv, _mm_set1_ps(EXIT_SCALE));
    unsigned neg = (unsigned)_mm_movemask_ps(_mm_cmplt_ps(inv, _mm_setzero_ps()));
    size_t row = sizeof(mt_real[4]);
    t->vo[0] = SPLAT(o, 0);
    t->vo[1] = SPLAT(o, 1);
    t->vo[2] = SPLAT(o, 2);
    t->vi[0] = SPLAT(inv, 0);
    t->vi[1] = SPLAT(inv, 1);
    t->vi[2] = SPLAT(inv, 2);
    t->vf[0] = SPLAT(far, 0);
    t->vf[1] = SPLAT(far, 1);
    t->vf[2] = SPLAT(far, 2);
    t->off[0] = (neg & 1) * row;
    t->off[1] = (2 + ((neg >> 1) & 1)) * row;
    t->off[2] = (4 + ((neg >> 2) & 1)) * row;
    t->off[3] = t->off[0] ^ row;
    t->off[4] = t->off[1] ^ row;
    t->off[5] = t->off[2] ^ row;
    t->ray = r;
    t->tri_ready = 0;
}
#else
static inline ALWAYS_INLINE void trav_init(trav *t, const mt_ray *r)
{
    int i;
    t->o[0] = r->o.x;
    t->o[1] = r->o.y;
    t->o[2] = r->o.z;
    t->inv[0] = 1 / r->d.x;
    t->inv[1] = 1 / r->d.y;
    t->inv[2] = 1 / r->d.z;
    t->nx = t->inv[0] < 0 ? 1 : 0;
    t->ny = t->inv[1] < 0 ? 3 : 2;
    t->nz = t->inv[2] < 0 ? 5 : 4;
    t->off[0] = (size_t)t->nx * sizeof(mt_real[4]);
    t->off[1] = (size_t)t->ny * sizeof(mt_real[4]);
    t->off[2] = (size_t)t->nz * sizeof(mt_real[4]);
    t->off[3] = (size_t)(t->nx ^ 1) * sizeof(mt_real[4]);
    t->off[4] = (size_t)(t->ny ^ 1) * sizeof(mt_real[4]);
    t->off[5] = (size_t)(t->nz ^ 1) * sizeof(mt_real[4]);
    /* folded into the inverse: the same number of roundings as scaling
     * each distance */
    for (i = 0; i < 3; ++i) t->inv_far[i] = t->inv[i] * EXIT_SCALE;
    t->ray = r;
    t->tri_ready = 0;
}
#endif

/* The triangle test's part: the shear of mt__tri_ray_init, at the first
 * triangle leaf (a ray that meets only quadrics never needs it). */
static inline void trav_init_tri(trav *t)
{
    mt__tri_ray_init(&t->tr, t->ray);
#if USE_SSE
    t->to[0] = _mm_set1_ps(t->tr.o[t->tr.kx]);
    t->to[1] = _mm_set1_ps(t->tr.o[t->tr.ky]);
    t->to[2] = _mm_set1_ps(t->tr.o[t->tr.kz]);
    t->ts[0] = _mm_set1_ps(t->tr.sx);
    t->ts[1] = _mm_set1_ps(t->tr.sy);
    t->ts[2] = _mm_set1_ps(t->tr.sz);
#endif
    t->tri_ready = 1;
}

/* Entry distances of the ray into the four children within [tmin, tmax];
 * returns the mask of children hit. Both versions drop a NaN candidate: the
 * comparisons put it first, and SSE's max and min return their second
 * operand when one is NaN. */
#if USE_SSE
static inline ALWAYS_INLINE unsigned node_hits(const trav *t, const mt__bvh_node *nd, __m128 tmin, __m128 tmax,
                                 mt_real tn_out[4])
{
    const char *base = (const char *)nd->b;
#define ROW(i) _mm_loadu_ps((const float *)(const void *)(base + t->off[i]))
    __m128 a = _mm_mul_ps(_mm_sub_ps(ROW(0), t->vo[0]), t->vi[0]);
    __m128 b = _mm_mul_ps(_mm_sub_ps(ROW(1), t->vo[1]), t->vi[1]);
    __m128 c = _mm_mul_ps(_mm_sub_ps(ROW(2), t->vo[2]), t->vi[2]);
    __m128 d = _mm_mul_ps(_mm_sub_ps(ROW(3), t->vo[0]), t->vf[0]);
    __m128 e = _mm_mul_ps(_mm_sub_ps(ROW(4), t->vo[1]), t->vf[1]);
    __m128 f = _mm_mul_ps(_mm_sub_ps(ROW(5), t->vo[2]), t->vf[2]);
#undef ROW
    __m128 n = _mm_max_ps(c, _mm_max_ps(b, _mm_max_ps(a, tmin)));
    __m128 x = _mm_min_ps(f, _mm_min_ps(e, _mm_min_ps(d, tmax)));
    _mm_storeu_ps(tn_out, n);
    return (unsigned)_mm_movemask_ps(_mm_cmple_ps(n, x));
}
typedef __m128 tbound;
static tbound to_bound(mt_real v) { return _mm_set1_ps(v); }
#else
static inline ALWAYS_INLINE unsigned node_hits(const trav *t, const mt__bvh_node *nd, mt_real tmin, mt_real tmax,
                                 mt_real tn_out[4])
{
    const mt_real *nxr = nd->b[t->nx], *fxr = nd->b[t->nx ^ 1];
    const mt_real *nyr = nd->b[t->ny], *fyr = nd->b[t->ny ^ 1];
    const mt_real *nzr = nd->b[t->nz], *fzr = nd->b[t->nz ^ 1];
    mt_real ox = t->o[0], oy = t->o[1], oz = t->o[2], ix = t->inv[0], iy = t->inv[1];
    mt_real iz = t->inv[2], jx = t->inv_far[0], jy = t->inv_far[1], jz = t->inv_far[2];
    unsigned mask = 0;
    int i;
    for (i = 0; i < 4; ++i) {
        mt_real a = (nxr[i] - ox) * ix, b = (nyr[i] - oy) * iy, c = (nzr[i] - oz) * iz;
        mt_real d = (fxr[i] - ox) * jx, e = (fyr[i] - oy) * jy, f = (fzr[i] - oz) * jz;
        mt_real n = tmin, x = tmax;
        n = a > n ? a : n;
        n = b > n ? b : n;
        n = c > n ? c : n;
        x = d < x ? d : x;
        x = e < x ? e : x;
        x = f < x ? f : x;
        tn_out[i] = n;
        mask |= (unsigned)(n <= x) << i;
    }
    return mask;
}
typedef mt_real tbound;
static tbound to_bound(mt_real v) { return v; }
#endif

/* Index of the lowest set bit of a non-zero 4-bit mask. */
static inline int low_bit(unsigned m)
{
    static const signed char tab[16] = {-1, 0, 1, 0, 2, 0, 1, 0, 3, 0, 1, 0, 2, 0, 1, 0};
    return tab[m & 15];
}

/* The four triangles of a packet against the ray: the mask of lanes hit in
 * [tmin, tmax], with their distances and barycentrics. mt__tri_hit's
 * operations in four lanes (so the answers are the same bits); *exact is
 * set, and nothing returned, when an edge function is exactly zero in some
 * lane: the caller then tests the lanes one by one, with the double-precision
 * recomputation of the scalar test. */
#if USE_SSE
static inline ALWAYS_INLINE unsigned tri4_hits(const trav *t, const mt__tri4 *q, __m128 tmin, __m128 tmax,
                                 mt_real tt[4], mt_real b1[4], mt_real b2[4], int *exact)
{
    const int kx = t->tr.kx, ky = t->tr.ky, kz = t->tr.kz;
    const __m128 zero = _mm_setzero_ps(), absm = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
    __m128 az = _mm_sub_ps(_mm_loadu_ps(q->v[0][kz]), t->to[2]);
    __m128 bz = _mm_sub_ps(_mm_loadu_ps(q->v[1][kz]), t->to[2]);
    __m128 cz = _mm_sub_ps(_mm_loadu_ps(q->v[2][kz]), t->to[2]);
    __m128 ax = _mm_sub_ps(_mm_sub_ps(_mm_loadu_ps(q->v[0][kx]), t->to[0]), _mm_mul_ps(t->ts[0], az));
    __m128 ay = _mm_sub_ps(_mm_sub_ps(_mm_loadu_ps(q->v[0][ky]), t->to[1]), _mm_mul_ps(t->ts[1], az));
    __m128 bx = _mm_sub_ps(_mm_sub_ps(_mm_loadu_ps(q->v[1][kx]), t->to[0]), _mm_mul_ps(t->ts[0], bz));
    __m128 by = _mm_sub_ps(_mm_sub_ps(_mm_loadu_ps(q->v[1][ky]), t->to[1]), _mm_mul_ps(t->ts[1], bz));
    __m128 cx = _mm_sub_ps(_mm_sub_ps(_mm_loadu_ps(q->v[2][kx]), t->to[0]), _mm_mul_ps(t->ts[0], cz));
    __m128 cy = _mm_sub_ps(_mm_sub_ps(_mm_loadu_ps(q->v[2][ky]), t->to[1]), _mm_mul_ps(t->ts[1], cz));
    __m128 e0 = _mm_sub_ps(_mm_mul_ps(bx, cy), _mm_mul_ps(by, cx));
    __m128 e1 = _mm_sub_ps(_mm_mul_ps(cx, ay), _mm_mul_ps(cy, ax));
    __m128 e2 = _mm_sub_ps(_mm_mul_ps(ax, by), _mm_mul_ps(ay, bx));
    __m128 rej, det, ts, inv, tv, valid, mzt, mxt, myt, dz, dx, dy, de, me, dt;
    if (_mm_movemask_ps(_mm_or_ps(_mm_or_ps(_mm_cmpeq_ps(e0, zero), _mm_cmpeq_ps(e1, zero)),
                                  _mm_cmpeq_ps(e2, zero)))) {
        *exact = 1;
        return 0;
    }
    rej = _mm_and_ps(_mm_or_ps(_mm_or_ps(_mm_cmplt_ps(e0, zero), _mm_cmplt_ps(e1, zero)), _mm_cmplt_ps(e2, zero)),
                     _mm_or_ps(_mm_or_ps(_mm_cmpgt_ps(e0, zero), _mm_cmpgt_ps(e1, zero)), _mm_cmpgt_ps(e2, zero)));
    if (_mm_movemask_ps(rej) == 15) return 0; /* the ray passes outside all four */
    det = _mm_add_ps(_mm_add_ps(e0, e1), e2);
    rej = _mm_or_ps(rej, _mm_cmpeq_ps(det, zero));
    az = _mm_mul_ps(az, t->ts[2]);
    bz = _mm_mul_ps(bz, t->ts[2]);
    cz = _mm_mul_ps(cz, t->ts[2]);
    ts = _mm_add_ps(_mm_add_ps(_mm_mul_ps(e0, az), _mm_mul_ps(e1, bz)), _mm_mul_ps(e2, cz));
    {
        __m128 dneg = _mm_cmplt_ps(det, zero);
        rej = _mm_or_ps(rej, _mm_or_ps(_mm_and_ps(dneg, _mm_cmpge_ps(ts, zero)),
                                       _mm_andnot_ps(dneg, _mm_cmple_ps(ts, zero))));
    }
    if (_mm_movemask_ps(rej) == 15) return 0;
    inv = _mm_div_ps(_mm_set1_ps(1), det);
    tv = _mm_mul_ps(ts, inv);
    valid = _mm_andnot_ps(rej, _mm_and_ps(_mm_cmpge_ps(tv, tmin), _mm_cmple_ps(tv, tmax)));
    if (!_mm_movemask_ps(valid)) return 0;
    mzt = _mm_max_ps(_mm_and_ps(az, absm), _mm_max_ps(_mm_and_ps(bz, absm), _mm_and_ps(cz, absm)));
    mxt = _mm_max_ps(_mm_and_ps(ax, absm), _mm_max_ps(_mm_and_ps(bx, absm), _mm_and_ps(cx, absm)));
    myt = _mm_max_ps(_mm_and_ps(ay, absm), _mm_max_ps(_mm_and_ps(by, absm), _mm_and_ps(cy, absm)));
    dz = _mm_mul_ps(_mm_set1_ps(mt__gamma(3)), mzt);
    dx = _mm_mul_ps(_mm_set1_ps(mt__gamma(5)), _mm_add_ps(mxt, mzt));
    dy = _mm_mul_ps(_mm_set1_ps(mt__gamma(5)), _mm_add_ps(myt, mzt));
    de = _mm_mul_ps(_mm_set1_ps(2), _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_mul_ps(_mm_set1_ps(mt__gamma(2)), mxt), myt),
                                                          _mm_mul_ps(dy, mxt)),
                                               _mm_mul_ps(dx, myt)));
    me = _mm_max_ps(_mm_and_ps(e0, absm), _mm_max_ps(_mm_and_ps(e1, absm), _mm_and_ps(e2, absm)));
    dt = _mm_mul_ps(_mm_mul_ps(_mm_set1_ps(3), _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_mul_ps(_mm_set1_ps(mt__gamma(3)), me), mzt),
                                                                     _mm_mul_ps(de, mzt)),
                                                          _mm_mul_ps(dz, me))),
                    _mm_and_ps(inv, absm));
    valid = _mm_and_ps(valid, _mm_cmpgt_ps(tv, dt));
    _mm_storeu_ps(tt, tv);
    _mm_storeu_ps(b1, _mm_mul_ps(e1, inv));
    _mm_storeu_ps(b2, _mm_mul_ps(e2, inv));
    return (unsigned)_mm_movemask_ps(valid);
}
#else
static inline ALWAYS_INLINE unsigned tri4_hits(const trav *t, const mt__tri4 *q, mt_real tmin, mt_real tmax,
                                 mt_real tt[4], mt_real b1[4], mt_real b2[4], int *exact)
{
    unsigned m = 0;
    int i;
    *exact = 0;
    for (i = 0; i < 4; ++i)
        if (mt__tri_hit(&t->tr, &q->v[0][0][i], &q->v[1][0][i], &q->v[2][0][i], 4, tmin, tmax,
                        &tt[i], &b1[i], &b2[i]))
            m |= 1u << i;
    return m;
}
#endif

typedef struct best {
    mt_real t, b1, b2;
    uint32_t id;
    int found, quad;
    mt_hit qhit;
} best;

/* A hint that the child will be read soon: the node's two cache lines or
 * the start of the leaf's triangles (GCC and clang; nothing elsewhere). */
#if defined(__GNUC__)
#define PREFETCH(p) __builtin_prefetch(p)
#else
#define PREFETCH(p) ((void)0)
#endif
static inline void prefetch_child(const mt_geometry *g, mt__bvh_ref c)
{
    if (c.count == 0) {
        const char *p = (const char *)&g->nodes[c.index];
        PREFETCH(p);
        PREFETCH(p + 64);
    } else if (c.kind == MT__LEAF_TRIS) {
        const char *p = (const char *)&g->tri[c.index];
        PREFETCH(p);
        PREFETCH(p + 64);
        PREFETCH(p + 128);
    }
}

/* Closest hit (any = 0) or any hit (any = 1): inlined into both callers so
 * that each is compiled for its constant. */
static inline ALWAYS_INLINE int traverse(const mt_geometry *g, const mt_ray *r, int any, best *bs)
{
    mt__bvh_ref stack[MT__BVH_STACK], cur = g->root;
    mt_real stack_t[MT__BVH_STACK], tmin = r->tmin, tmax = r->tmax, limit;
    tbound vtmin = to_bound(tmin), vlimit;
    unsigned sp = 0;
    trav t;
    bs->found = 0;
    bs->t = bs->b1 = bs->b2 = 0;
    bs->id = 0;
    bs->quad = 0;
    if (g->stats.prims == 0) return 0;
    trav_init(&t, r);
    /* a leaf at the root is entered only through the scene's box; an inner
     * root's own test of its children costs the same as that box's */
    if (cur.count != 0) {
        mt_real tn[4];
        if (!(node_hits(&t, &g->root_node, vtmin, to_bound(tmax), tn) & 1)) return 0;
    }
    limit = tmax * PRUNE_SCALE;
    vlimit = to_bound(limit);
    for (;;) {
        if (cur.count == 0) {
            const mt__bvh_node *nd = &g->nodes[cur.index];
            mt_real tn[4];
            unsigned mask = node_hits(&t, nd, vtmin, vlimit, tn);
            if (mask) {
                int i0 = low_bit(mask);
                mask &= mask - 1;
                if (!mask) {
                    cur = nd->c[i0];
                    continue;
                } else if (any) {
                    /* any hit: no need for order */
                    while (mask) {
                        int b = low_bit(mask);
                        mask &= mask - 1;
                        prefetch_child(g, nd->c[b]);
                        stack[sp++] = nd->c[b];
                    }
                    cur = nd->c[i0];
                    continue;
                } else {
                    /* sort the hit children by entry distance (at most 4) */
                    int idx[4], n = 0, i, j;
                    idx[n++] = i0;
                    while (mask) {
                        int b = low_bit(mask);
                        mask &= mask - 1;
                        for (j = n++; j > 0 && tn[idx[j - 1]] < tn[b]; --j) idx[j] = idx[j - 1];
                        idx[j] = b;
                    }
                    /* idx is farthest first: stack all but the last */
                    for (i = 0; i < n - 1; ++i) {
                        prefetch_child(g, nd->c[idx[i]]);
                        stack[sp] = nd->c[idx[i]];
                        stack_t[sp++] = tn[idx[i]];
                    }
                    cur = nd->c[idx[n - 1]];
                    continue;
                }
            }
        } else if (cur.kind == MT__LEAF_TRIS) {
            uint32_t p, np = (cur.count + 3u) / 4u;
            if (!t.tri_ready) trav_init_tri(&t);
            for (p = 0; p < np; ++p) {
                const mt__tri4 *q = &g->tri[cur.index + p];
                const uint32_t *ids = g->tri_id + 4 * ((size_t)cur.index + p);
                mt_real tt[4], b1[4], b2[4];
                int exact = 0;
                unsigned m = tri4_hits(&t, q, vtmin, to_bound(tmax), tt, b1, b2, &exact);
                if (exact) {
                    /* an exact zero edge function: lane by lane, the scalar test */
                    int i;
                    for (i = 0; i < 4; ++i)
                        if (mt__tri_hit(&t.tr, &q->v[0][0][i], &q->v[1][0][i], &q->v[2][0][i], 4,
                                        tmin, tmax, &tt[i], &b1[i], &b2[i]))
                            m |= 1u << i;
                }
                if (m && any) return 1;
                while (m) {
                    int i = low_bit(m);
                    m &= m - 1;
                    /* the four were tested against the tmax before this packet */
                    if (tt[i] > tmax) continue;
                    if (tt[i] < tmax || !bs->found || ids[i] < bs->id) {
                        bs->t = tmax = tt[i];
                        bs->b1 = b1[i];
                        bs->b2 = b2[i];
                        bs->id = ids[i];
                        bs->found = 1;
                        bs->quad = 0;
                        limit = tmax * PRUNE_SCALE;
                        vlimit = to_bound(limit);
                    }
                }
            }
        } else {
            uint32_t i;
            for (i = 0; i < cur.count; ++i) {
                mt_hit h;
                uint32_t id = g->quad_id[cur.index + i];
                if (!mt__quadric_intersect_to(g->quad[cur.index + i], r, tmax, any ? NULL : &h)) continue;
                if (any) return 1;
                if (h.t < tmax || !bs->found || id < bs->id) {
                    bs->t = tmax = h.t;
                    bs->id = id;
                    bs->found = 1;
                    bs->quad = 1;
                    bs->qhit = h;
                    limit = tmax * PRUNE_SCALE;
                    vlimit = to_bound(limit);
                }
            }
        }
        if (any) {
            /* nothing to prune: every stacked child is still in [tmin, tmax] */
            if (sp == 0) return 0;
            cur = stack[--sp];
            continue;
        }
        for (;;) {
            if (sp == 0) return bs->found;
            --sp;
            if (stack_t[sp] <= limit) break;
        }
        cur = stack[sp];
    }
}

int mt_geometry_intersect(const mt_geometry *g, const mt_ray *r, mt_hit *hit)
{
    best bs;
    if (!g->committed || !traverse(g, r, 0, &bs)) return 0;
    if (bs.quad) *hit = bs.qhit;
    else {
        hit->b1 = bs.b1;
        hit->b2 = bs.b2;
        hit->pobj[0] = hit->pobj[1] = hit->pobj[2] = 0;
    }
    hit->t = bs.t;
    hit->id = bs.id;
    hit->shape = mt_geometry_prim(g, bs.id, &hit->prim);
    return 1;
}

int mt_geometry_occluded(const mt_geometry *g, const mt_ray *r)
{
    best bs;
    return g->committed && traverse(g, r, 1, &bs);
}
