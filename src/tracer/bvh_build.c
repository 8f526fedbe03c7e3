/*
 * The BVH builder: top-down binned SAH (Wald, "On fast Construction of
 * SAH-based Bounding Volume Hierarchies", 2007) over all three axes in one
 * pass, with an explicit work stack. A four-wide node is made by splitting
 * its range in two and then splitting the child of largest surface area
 * again until there are four children or none is worth splitting (the
 * collapse of a binary SAH tree, done on the fly). Nodes come out
 * depth-first, and the leaves' primitives are copied into contiguous arrays
 * in the order traversal reads them.
 *
 * Cost model of a binary split: a node visit costs MT__BVH_TRAVERSAL_COST
 * triangle tests; a leaf costs its triangles plus MT__BVH_QUADRIC_COST per
 * quadric. A range is a leaf when
 * it is small enough and no split pays; ranges whose centroids coincide are
 * halved by index; from depth MT__BVH_SAH_DEPTH on the median is taken.
 */
#include <string.h>
#include "core/alloc.h"
#include "tracer/bvh.h"

#define NBINS 16
#define MT__BVH_TRAVERSAL_COST 3.0
/* A quadric test (double precision, a square root, clipping) costs about
 * eight triangle tests: weighted so, two spheres do not share a leaf. */
#define MT__BVH_QUADRIC_COST 8.0

typedef struct prim {
    mt_real lo[3], hi[3], c[3];
    uint32_t id, shape, local;
    int quad;
} prim;

typedef struct box {
    mt_real lo[3], hi[3];
} box;

enum { HOW_LEAF, HOW_SAH, HOW_KIND, HOW_MEDIAN };

/* A range of primitives and what to do with it. */
typedef struct range {
    uint32_t start, end, nquad;
    box bb, cb; /* bounds of the primitives and of their centroids */
    int how, axis, bin; /* HOW_SAH: left = bins <= bin on axis; HOW_MEDIAN: axis, -1 by index */
} range;

typedef struct task {
    range r;
    int32_t parent; /* node index, -1 for the root */
    int slot;
    uint32_t depth;
} task;

typedef struct builder {
    mt_geometry *g;
    prim *p;
    task *stack;
    uint32_t nstack, stack_cap;
    double root_area;
} builder;

static void box_empty(box *b)
{
    int i;
    for (i = 0; i < 3; ++i) {
        b->lo[i] = MT_REAL_MAX;
        b->hi[i] = -MT_REAL_MAX;
    }
}
static void box_add(box *b, const mt_real lo[3], const mt_real hi[3])
{
    int i;
    for (i = 0; i < 3; ++i) {
        b->lo[i] = lo[i] < b->lo[i] ? lo[i] : b->lo[i];
        b->hi[i] = hi[i] > b->hi[i] ? hi[i] : b->hi[i];
    }
}
/* Half the surface area (the SAH only needs ratios); 0 when empty. */
static double box_area(const box *b)
{
    double dx = (double)b->hi[0] - b->lo[0], dy = (double)b->hi[1] - b->lo[1];
    double dz = (double)b->hi[2] - b->lo[2];
    if (dx < 0 || dy < 0 || dz < 0) return 0;
    return dx * dy + dy * dz + dz * dx;
}

static mt_real bin_scale(const box *cb, int a)
{
    mt_real ext = cb->hi[a] - cb->lo[a];
    return ext > 0 ? (mt_real)NBINS * (1 - (mt_real)1e-6) / ext : 0;
}
static int bin_of(mt_real c, mt_real cmin, mt_real k)
{
    int b = (int)((c - cmin) * k);
    return b < 0 ? 0 : (b >= NBINS ? NBINS - 1 : b);
}

/* The cheapest of the NBINS - 1 planes on each axis, binned in one pass;
 * *cost is the SAH cost of the best split (1e300 when there is none). */
static void find_split(const prim *p, uint32_t n, const box *cb, double area, int *axis,
                       int *bin, double *cost)
{
    box bins[3][NBINS];
    double cnt[3][NBINS], total = 0; /* weighted counts */
    uint32_t j;
    mt_real k[3];
    int a, i;
    *axis = -1;
    *bin = 0;
    *cost = 1e300;
    for (a = 0; a < 3; ++a) {
        k[a] = bin_scale(cb, a);
        for (i = 0; i < NBINS; ++i) {
            box_empty(&bins[a][i]);
            cnt[a][i] = 0;
        }
    }
    for (j = 0; j < n; ++j) {
        double w = p[j].quad ? MT__BVH_QUADRIC_COST : 1;
        total += w;
        for (a = 0; a < 3; ++a) {
            int b = bin_of(p[j].c[a], cb->lo[a], k[a]);
            cnt[a][b] += w;
            box_add(&bins[a][b], p[j].lo, p[j].hi);
        }
    }
    for (a = 0; a < 3; ++a) {
        box acc;
        double right[NBINS], nr = 0, nl = 0;
        if (k[a] == 0) continue;
        box_empty(&acc);
        for (i = NBINS - 1; i > 0; --i) {
            box_add(&acc, bins[a][i].lo, bins[a][i].hi);
            nr += cnt[a][i];
            right[i] = box_area(&acc) * nr;
        }
        box_empty(&acc);
        for (i = 0; i < NBINS - 1; ++i) {
            double c;
            box_add(&acc, bins[a][i].lo, bins[a][i].hi);
            nl += cnt[a][i];
            if (nl == 0 || nl == total) continue; /* sums of small integers: exact */
            c = MT__BVH_TRAVERSAL_COST + (box_area(&acc) * nl + right[i + 1]) / area;
            if (c < *cost) {
                *cost = c;
                *axis = a;
                *bin = i;
            }
        }
    }
}

/* Bounds of the range and the decision about it. */
static void analyze(builder *b, range *r, uint32_t depth)
{
    const prim *p = b->p + r->start;
    uint32_t n = r->end - r->start, i;
    double area, cost = 1e300;
    int a;
    box_empty(&r->bb);
    box_empty(&r->cb);
    r->nquad = 0;
    for (i = 0; i < n; ++i) {
        box_add(&r->bb, p[i].lo, p[i].hi);
        box_add(&r->cb, p[i].c, p[i].c);
        r->nquad += p[i].quad != 0;
    }
    r->axis = -1;
    r->bin = 0;
    area = box_area(&r->bb);
    if (n > 1 && depth < MT__BVH_SAH_DEPTH && area > 0)
        find_split(p, n, &r->cb, area, &r->axis, &r->bin, &cost);
    if (n == 1 || (n <= MT__BVH_LEAF_MAX && (r->nquad == 0 || r->nquad == n) &&
                   cost >= (n - r->nquad) + MT__BVH_QUADRIC_COST * r->nquad)) {
        r->how = HOW_LEAF;
    } else if (n <= MT__BVH_LEAF_MAX && r->nquad > 0 && r->nquad < n) {
        r->how = HOW_KIND;
    } else if (r->axis >= 0) {
        r->how = HOW_SAH;
    } else {
        /* no useful plane (coincident centroids, or too deep for the SAH):
         * the median of the widest centroid extent, or halves by index */
        r->how = HOW_MEDIAN;
        for (a = 0; a < 3; ++a)
            if (r->cb.hi[a] > r->cb.lo[a] &&
                (r->axis < 0 || r->cb.hi[a] - r->cb.lo[a] > r->cb.hi[r->axis] - r->cb.lo[r->axis]))
                r->axis = a;
    }
}

static void swap_prims(prim *a, prim *b)
{
    prim t = *a;
    *a = *b;
    *b = t;
}

/* Quickselect: p[m] gets the element of rank m by centroid on axis, smaller
 * ones before it, larger after (std::nth_element). */
static void nth_element(prim *p, uint32_t n, uint32_t m, int axis)
{
    uint32_t lo = 0, hi = n - 1;
    while (lo < hi) {
        mt_real pivot = p[lo + (hi - lo) / 2].c[axis];
        uint32_t i = lo, j = hi;
        while (i <= j) {
            while (p[i].c[axis] < pivot) ++i;
            while (p[j].c[axis] > pivot) --j;
            if (i <= j) {
                swap_prims(&p[i], &p[j]);
                ++i;
                if (j == 0) break;
                --j;
            }
        }
        if (m <= j) hi = j;
        else if (m >= i) lo = i;
        else break;
    }
}

/* Splits r (not a leaf) into two analyzed ranges. */
static void apply_split(builder *b, const range *r, uint32_t depth, range *left, range *right)
{
    prim *p = b->p + r->start;
    uint32_t n = r->end - r->start, i = 0, j = n, mid;
    if (r->how == HOW_SAH) {
        mt_real k = bin_scale(&r->cb, r->axis), lo = r->cb.lo[r->axis];
        while (i < j) {
            if (bin_of(p[i].c[r->axis], lo, k) <= r->bin) ++i;
            else swap_prims(&p[i], &p[--j]);
        }
        mid = i;
    } else if (r->how == HOW_KIND) {
        while (i < j) {
            if (!p[i].quad) ++i;
            else swap_prims(&p[i], &p[--j]);
        }
        mid = i;
    } else {
        mid = n / 2;
        if (r->axis >= 0) nth_element(p, n, mid, r->axis);
    }
    if (mid == 0 || mid == n) mid = n / 2; /* cannot happen; keeps the build finite */
    left->start = r->start;
    left->end = right->start = r->start + mid;
    right->end = r->end;
    analyze(b, left, depth);
    analyze(b, right, depth);
}

static mt_status push(builder *b, const range *r, int32_t parent, int slot, uint32_t depth,
                      mt_error *err)
{
    task *t;
    if (b->nstack == b->stack_cap) {
        uint32_t cap = b->stack_cap ? 2 * b->stack_cap : 64;
        task *s = mt__realloc(b->stack, cap * sizeof *s);
        if (!s) return mt_error_set(err, MT_ERR_NOMEM, "out of memory building the BVH");
        b->stack = s;
        b->stack_cap = cap;
    }
    t = &b->stack[b->nstack++];
    t->r = *r;
    t->parent = parent;
    t->slot = slot;
    t->depth = depth;
    return MT_OK;
}

static void emit_leaf(builder *b, const range *r, mt__bvh_ref *ref)
{
    mt_geometry *g = b->g;
    uint32_t i, n = r->end - r->start;
    const prim *p = b->p + r->start;
    if (p[0].quad) {
        ref->index = g->nquad;
        ref->kind = MT__LEAF_QUADRICS;
        for (i = 0; i < n; ++i) {
            g->quad[g->nquad] = g->shapes[p[i].shape];
            g->quad_id[g->nquad++] = p[i].id;
        }
    } else {
        ref->index = g->ntri;
        ref->kind = MT__LEAF_TRIS;
        for (i = 0; i < (n + 3) / 4 * 4; ++i) {
            mt__tri4 *dst = &g->tri[g->ntri + i / 4];
            int k, lane = (int)(i % 4);
            if (i < n) {
                const mt_shape *s = g->shapes[p[i].shape];
                const int *v = s->indices + 3 * (size_t)p[i].local;
                for (k = 0; k < 3; ++k) {
                    dst->v[k][0][lane] = s->P[v[k]].x;
                    dst->v[k][1][lane] = s->P[v[k]].y;
                    dst->v[k][2][lane] = s->P[v[k]].z;
                }
                g->tri_id[4 * (size_t)g->ntri + i] = p[i].id;
            } else {
                for (k = 0; k < 9; ++k) dst->v[k / 3][k % 3][lane] = (mt_real)NAN;
                g->tri_id[4 * (size_t)g->ntri + i] = UINT32_MAX;
            }
        }
        g->ntri += (n + 3) / 4;
    }
    ref->count = (uint16_t)n;
    g->stats.leaves++;
    if (n > g->stats.max_leaf_prims) g->stats.max_leaf_prims = n;
    if (b->root_area > 0)
        g->stats.sah_cost += (p[0].quad ? MT__BVH_QUADRIC_COST : 1) * n * box_area(&r->bb) / b->root_area;
}

/* One four-wide node from a range that is not a leaf. */
static mt_status build_node(builder *b, const task *t, mt_error *err)
{
    mt_geometry *g = b->g;
    uint32_t idx = g->nnodes++, k;
    mt__bvh_node *nd = &g->nodes[idx];
    range ch[4];
    int n = 1, i, a;
    mt__bvh_ref *ref = t->parent < 0 ? &g->root : &g->nodes[t->parent].c[t->slot];
    ref->index = idx;
    ref->count = 0;
    ref->kind = 0;
    if (t->depth + 1 > g->stats.max_depth) g->stats.max_depth = t->depth + 1;
    g->stats.inner_nodes++;
    if (b->root_area > 0) g->stats.sah_cost += MT__BVH_TRAVERSAL_COST * box_area(&t->r.bb) / b->root_area;
    ch[0] = t->r;
    while (n < 4) {
        int best = -1;
        double best_area = -1;
        for (i = 0; i < n; ++i)
            if (ch[i].how != HOW_LEAF && box_area(&ch[i].bb) > best_area) {
                best = i;
                best_area = box_area(&ch[i].bb);
            }
        if (best < 0) break;
        {
            range whole = ch[best];
            apply_split(b, &whole, t->depth + 1, &ch[best], &ch[n]);
            ++n;
        }
    }
    for (i = 0; i < 4; ++i)
        for (a = 0; a < 3; ++a) {
            nd->b[2 * a][i] = i < n ? ch[i].bb.lo[a] : MT_REAL_MAX;
            nd->b[2 * a + 1][i] = i < n ? ch[i].bb.hi[a] : -MT_REAL_MAX;
        }
    memset(nd->c, 0, sizeof nd->c);
    for (i = 0; i < n; ++i)
        if (ch[i].how == HOW_LEAF) emit_leaf(b, &ch[i], &nd->c[i]);
    /* inner children in reverse, so that the first is built next and its
     * node follows this one */
    for (k = (uint32_t)n; k-- > 0;)
        if (ch[k].how != HOW_LEAF) {
            mt_status st = push(b, &ch[k], (int32_t)idx, (int)k, t->depth + 1, err);
            if (st != MT_OK) return st;
        }
    return MT_OK;
}

static mt_status gather(builder *b, mt_error *err)
{
    mt_geometry *g = b->g;
    uint32_t total = g->base[g->nshapes], si, k = 0, ntri = 0, nquad = 0, j;
    b->p = mt__malloc((size_t)total * sizeof *b->p);
    if (!b->p) return mt_error_set(err, MT_ERR_NOMEM, "out of memory building the BVH");
    for (si = 0; si < g->nshapes; ++si) {
        const mt_shape *s = g->shapes[si];
        uint32_t n = mt__shape_nprims(s);
        for (j = 0; j < n; ++j, ++k) {
            prim *p = &b->p[k];
            mt_vec3 lo, hi;
            int a;
            mt_shape_prim_bounds(s, j, &lo, &hi);
            p->lo[0] = lo.x, p->lo[1] = lo.y, p->lo[2] = lo.z;
            p->hi[0] = hi.x, p->hi[1] = hi.y, p->hi[2] = hi.z;
            for (a = 0; a < 3; ++a) p->c[a] = (mt_real)0.5 * p->lo[a] + (mt_real)0.5 * p->hi[a];
            p->id = k;
            p->shape = si;
            p->local = j;
            p->quad = s->kind != MT_SHAPE_TRIANGLES;
            if (p->quad) nquad++;
            else ntri++;
        }
    }
    /* at most one partly filled packet per leaf, and a leaf holds at least
     * one triangle: ntri packets suffice */
    g->tri = mt__malloc(((size_t)ntri + 1) * sizeof *g->tri);
    g->tri_id = mt__malloc(4 * ((size_t)ntri + 1) * sizeof *g->tri_id);
    g->quad = mt__malloc(((size_t)nquad + 1) * sizeof *g->quad);
    g->quad_id = mt__malloc(((size_t)nquad + 1) * sizeof *g->quad_id);
    /* each node has at least two children: at most total - 1 nodes;
     * 64-byte alignment for the cache lines */
    g->nodes_mem = mt__malloc(((size_t)total + 1) * sizeof *g->nodes + 64);
    if (!g->tri || !g->tri_id || !g->quad || !g->quad_id || !g->nodes_mem)
        return mt_error_set(err, MT_ERR_NOMEM, "out of memory building the BVH");
    g->nodes = (mt__bvh_node *)(void *)(((uintptr_t)g->nodes_mem + 63) & ~(uintptr_t)63);
    return MT_OK;
}

void mt__bvh_free(mt_geometry *g)
{
    mt__free(g->nodes_mem);
    mt__free(g->tri);
    mt__free(g->tri_id);
    mt__free(g->quad);
    mt__free(g->quad_id);
    g->nodes_mem = NULL;
    g->nodes = NULL;
    g->tri = NULL;
    g->tri_id = NULL;
    g->quad = NULL;
    g->quad_id = NULL;
    g->nnodes = g->ntri = g->nquad = 0;
}

mt_status mt__bvh_build(mt_geometry *g, mt_error *err)
{
    builder b;
    uint32_t total = g->base[g->nshapes];
    mt_status st = MT_OK;
    memset(&b, 0, sizeof b);
    memset(&g->stats, 0, sizeof g->stats);
    b.g = g;
    memset(&g->root, 0, sizeof g->root);
    if (total == 0) return MT_OK;
    if ((st = gather(&b, err)) == MT_OK) {
        range all;
        int a;
        all.start = 0;
        all.end = total;
        analyze(&b, &all, 0);
        b.root_area = box_area(&all.bb);
        memset(&g->root_node, 0, sizeof g->root_node);
        for (a = 0; a < 3; ++a) {
            int k;
            g->root_box[2 * a] = all.bb.lo[a];
            g->root_box[2 * a + 1] = all.bb.hi[a];
            for (k = 0; k < 4; ++k) {
                g->root_node.b[2 * a][k] = k == 0 ? all.bb.lo[a] : MT_REAL_MAX;
                g->root_node.b[2 * a + 1][k] = k == 0 ? all.bb.hi[a] : -MT_REAL_MAX;
            }
        }
        if (all.how == HOW_LEAF) {
            emit_leaf(&b, &all, &g->root);
        } else {
            st = push(&b, &all, -1, 0, 0, err);
        }
        while (st == MT_OK && b.nstack > 0) {
            task t = b.stack[--b.nstack];
            st = build_node(&b, &t, err);
        }
    }
    mt__free(b.p);
    mt__free(b.stack);
    if (st != MT_OK) {
        mt__bvh_free(g);
        return st;
    }
    g->stats.prims = total;
    g->stats.bytes = g->nnodes * sizeof *g->nodes + g->ntri * (sizeof *g->tri + 16) +
                     g->nquad * (sizeof(void *) + 4);
    return MT_OK;
}
