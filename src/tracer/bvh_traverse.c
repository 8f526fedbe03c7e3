/*
 * BVH queries: closest hit and any hit. Read-only on the geometry, no
 * recursion, no allocation: a fixed stack of (child, entry distance).
 *
 * Per ray the inverse direction, the slab order by direction sign and the
 * triangle test's shear are computed once. Each node visit tests both
 * children's boxes (Williams et al.'s slab test, robust after Ize, "Robust
 * BVH Ray Traversal", JCGT 2013: exit distances are scaled by 1 + 2
 * gamma(3), and a NaN from 0 * Inf -- a ray in a slab's plane -- is ignored
 * rather than propagated), descends into the nearer, and stacks the farther
 * with its entry distance, which is checked again when it is popped.
 */
#include "tracer/bvh.h"
#include "tracer/triangle.h"

typedef struct trav {
    mt__tri_ray tr;
    mt_real o[3], inv[3];
    int n0, n1, n2; /* rows of the near planes for x, y, z (the far ones: 1 - row parity) */
    mt_real exit_scale, prune_scale;
} trav;

static void trav_init(trav *t, const mt_ray *r)
{
    t->o[0] = r->o.x;
    t->o[1] = r->o.y;
    t->o[2] = r->o.z;
    t->inv[0] = 1 / r->d.x;
    t->inv[1] = 1 / r->d.y;
    t->inv[2] = 1 / r->d.z;
    t->n0 = t->inv[0] < 0 ? 1 : 0;
    t->n1 = t->inv[1] < 0 ? 3 : 2;
    t->n2 = t->inv[2] < 0 ? 5 : 4;
    t->exit_scale = 1 + 2 * mt__gamma(3);
    /* a node is skipped only when it starts beyond the current closest hit
     * by more than the error of either distance (a few ulps), so that equal
     * or nearly equal hits on box faces -- shared vertices and edges -- are
     * all seen and resolved by id, as a brute-force search resolves them */
    t->prune_scale = 1 + 64 * MT_REAL_EPSILON;
    mt__tri_ray_init(&t->tr, r);
}

/* Entry distance of the ray into child c of node b (within [tmin, tmax]), or
 * a value above tmax when it misses. */
static inline mt_real child_entry(const trav *t, const mt_real (*b)[2], int c, mt_real tmin,
                                  mt_real tmax)
{
    mt_real tn = tmin, tf = tmax, x;
    x = (b[t->n0][c] - t->o[0]) * t->inv[0];
    tn = x > tn ? x : tn;
    x = (b[t->n1][c] - t->o[1]) * t->inv[1];
    tn = x > tn ? x : tn;
    x = (b[t->n2][c] - t->o[2]) * t->inv[2];
    tn = x > tn ? x : tn;
    x = (b[1 - t->n0][c] - t->o[0]) * t->inv[0] * t->exit_scale;
    tf = x < tf ? x : tf;
    x = (b[5 - t->n1][c] - t->o[1]) * t->inv[1] * t->exit_scale;
    tf = x < tf ? x : tf;
    x = (b[9 - t->n2][c] - t->o[2]) * t->inv[2] * t->exit_scale;
    tf = x < tf ? x : tf;
    return tn <= tf ? tn : MT_REAL_MAX;
}

typedef struct best {
    mt_real t, b1, b2;
    uint32_t id;
    int found, quad;
    mt_hit qhit;
} best;

/* Closest hit (any = 0) or any hit (any = 1); the compiler specializes the
 * two calls. */
static inline int traverse(const mt_geometry *g, const mt_ray *r, int any, best *bs)
{
    mt__bvh_ref stack[MT__BVH_STACK], cur = g->root;
    mt_real stack_t[MT__BVH_STACK], tmin = r->tmin, tmax = r->tmax, limit;
    unsigned sp = 0;
    trav t;
    bs->found = 0;
    if (g->root.kind == 0 && g->nnodes == 0) return 0;
    trav_init(&t, r);
    {
        /* the root box, laid out as one column */
        mt_real rb[6][2];
        int i;
        for (i = 0; i < 6; ++i) rb[i][0] = rb[i][1] = g->root_box[i];
        if (child_entry(&t, (const mt_real(*)[2])rb, 0, tmin, tmax) == MT_REAL_MAX) return 0;
    }
    limit = tmax * t.prune_scale;
    for (;;) {
        if (cur.kind == 0) {
            const mt__bvh_node *nd = &g->nodes[cur.index];
            mt_real t0 = child_entry(&t, (const mt_real(*)[2])nd->b, 0, tmin, limit);
            mt_real t1 = child_entry(&t, (const mt_real(*)[2])nd->b, 1, tmin, limit);
            if (t0 != MT_REAL_MAX) {
                if (t1 != MT_REAL_MAX) {
                    int first = t1 < t0;
                    stack[sp] = nd->c[!first];
                    stack_t[sp++] = first ? t0 : t1;
                    cur = nd->c[first];
                } else {
                    cur = nd->c[0];
                }
                continue;
            }
            if (t1 != MT_REAL_MAX) {
                cur = nd->c[1];
                continue;
            }
        } else if (cur.kind == MT__LEAF_TRIS) {
            const mt_real *v = g->tri + 9 * (size_t)cur.index;
            uint32_t i;
            for (i = 0; i < cur.count; ++i, v += 9) {
                mt_real th, b1, b2;
                uint32_t id;
                if (!mt__tri_hit(&t.tr, v, v + 3, v + 6, tmin, tmax, &th, &b1, &b2)) continue;
                if (any) return 1;
                id = g->tri_id[cur.index + i];
                if (th < tmax || !bs->found || id < bs->id) {
                    bs->t = tmax = th;
                    bs->b1 = b1;
                    bs->b2 = b2;
                    bs->id = id;
                    bs->found = 1;
                    bs->quad = 0;
                    limit = tmax * t.prune_scale;
                }
            }
        } else {
            uint32_t i;
            for (i = 0; i < cur.count; ++i) {
                mt_ray rr = *r;
                mt_hit h;
                uint32_t id = g->quad_id[cur.index + i];
                rr.tmax = tmax;
                if (!mt__quadric_intersect(g->quad[cur.index + i], &rr, &h)) continue;
                if (any) return 1;
                if (h.t < tmax || !bs->found || id < bs->id) {
                    bs->t = tmax = h.t;
                    bs->id = id;
                    bs->found = 1;
                    bs->quad = 1;
                    bs->qhit = h;
                    limit = tmax * t.prune_scale;
                }
            }
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
