/*
 * The BVH builder: top-down, binned SAH (Wald, "On fast Construction of
 * SAH-based Bounding Volume Hierarchies", 2007) over all three axes, with
 * an explicit work stack; the nodes come out depth-first (a node's first
 * child follows it) and the leaves' primitives are copied into contiguous
 * arrays in the order traversal reads them.
 *
 * Cost model: visiting a node (two box tests) costs about one triangle
 * test, MT__BVH_TRAVERSAL_COST; a leaf costs its primitive count. A range is
 * a leaf when it is small enough and splitting does not pay; ranges whose
 * centroids coincide are halved by index; below depth MT__BVH_SAH_DEPTH
 * the median is taken, which bounds the depth by the traversal stack.
 */
#include <string.h>
#include "core/alloc.h"
#include "tracer/bvh.h"

#define NBINS 16
#define MT__BVH_TRAVERSAL_COST 1.0

typedef struct prim {
    mt_real lo[3], hi[3], c[3];
    uint32_t id, shape, local;
    int quad;
} prim;

typedef struct task {
    uint32_t start, end, depth;
    int32_t parent; /* node index, -1 for the root */
    int slot;
} task;

typedef struct box {
    mt_real lo[3], hi[3];
} box;

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
        if (lo[i] < b->lo[i]) b->lo[i] = lo[i];
        if (hi[i] > b->hi[i]) b->hi[i] = hi[i];
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

typedef struct builder {
    mt_geometry *g;
    prim *p;
    task *stack;
    uint32_t nstack, stack_cap;
    double root_area;
} builder;

static int bin_of(mt_real c, mt_real cmin, mt_real k)
{
    int b = (int)((c - cmin) * k);
    return b < 0 ? 0 : (b >= NBINS ? NBINS - 1 : b);
}

typedef struct split {
    int axis, bin; /* bin: the last bin of the left side; axis -1: none */
    double cost;
} split;

/* The cheapest of the NBINS - 1 planes on each axis, by binned SAH. */
static split find_split(const prim *p, uint32_t n, const box *cb, double area)
{
    split best;
    int a, i;
    best.axis = -1;
    best.bin = 0;
    best.cost = 1e300;
    for (a = 0; a < 3; ++a) {
        box bins[NBINS], acc;
        uint32_t cnt[NBINS], j, left;
        double right_cost[NBINS];
        mt_real ext = cb->hi[a] - cb->lo[a], k;
        if (!(ext > 0)) continue;
        k = (mt_real)NBINS * (1 - (mt_real)1e-6) / ext;
        for (i = 0; i < NBINS; ++i) {
            box_empty(&bins[i]);
            cnt[i] = 0;
        }
        for (j = 0; j < n; ++j) {
            int b = bin_of(p[j].c[a], cb->lo[a], k);
            cnt[b]++;
            box_add(&bins[b], p[j].lo, p[j].hi);
        }
        box_empty(&acc);
        for (i = NBINS - 1, j = 0; i > 0; --i) {
            box_add(&acc, bins[i].lo, bins[i].hi);
            j += cnt[i];
            right_cost[i] = box_area(&acc) * j;
        }
        box_empty(&acc);
        for (i = 0, left = 0; i < NBINS - 1; ++i) {
            double c;
            box_add(&acc, bins[i].lo, bins[i].hi);
            left += cnt[i];
            if (left == 0 || left == n) continue;
            c = MT__BVH_TRAVERSAL_COST + (box_area(&acc) * left + right_cost[i + 1]) / area;
            if (c < best.cost) {
                best.cost = c;
                best.axis = a;
                best.bin = i;
            }
        }
    }
    return best;
}

static void swap_prims(prim *a, prim *b)
{
    prim t = *a;
    *a = *b;
    *b = t;
}

/* Moves the primitives for which pred holds to the front; returns their count. */
static uint32_t partition_bins(prim *p, uint32_t n, int axis, int last_bin, const box *cb)
{
    mt_real k = (mt_real)NBINS * (1 - (mt_real)1e-6) / (cb->hi[axis] - cb->lo[axis]);
    uint32_t i = 0, j = n;
    while (i < j) {
        if (bin_of(p[i].c[axis], cb->lo[axis], k) <= last_bin) ++i;
        else swap_prims(&p[i], &p[--j]);
    }
    return i;
}
static uint32_t partition_kind(prim *p, uint32_t n)
{
    uint32_t i = 0, j = n;
    while (i < j) {
        if (!p[i].quad) ++i;
        else swap_prims(&p[i], &p[--j]);
    }
    return i;
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

static mt_status push(builder *b, uint32_t start, uint32_t end, uint32_t depth, int32_t parent,
                      int slot, mt_error *err)
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
    t->start = start;
    t->end = end;
    t->depth = depth;
    t->parent = parent;
    t->slot = slot;
    return MT_OK;
}

static void emit_leaf(builder *b, const task *t, mt__bvh_ref *ref)
{
    mt_geometry *g = b->g;
    uint32_t i, n = t->end - t->start;
    const prim *p = b->p + t->start;
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
        for (i = 0; i < n; ++i) {
            const mt_shape *s = g->shapes[p[i].shape];
            const int *v = s->indices + 3 * (size_t)p[i].local;
            mt_real *dst = g->tri + 9 * (size_t)g->ntri;
            int k;
            for (k = 0; k < 3; ++k) {
                dst[3 * k] = s->P[v[k]].x;
                dst[3 * k + 1] = s->P[v[k]].y;
                dst[3 * k + 2] = s->P[v[k]].z;
            }
            g->tri_id[g->ntri++] = p[i].id;
        }
    }
    ref->count = (uint16_t)n;
    g->stats.leaves++;
    if (n > g->stats.max_leaf_prims) g->stats.max_leaf_prims = n;
}

static mt_status build_task(builder *b, const task *t, mt_error *err)
{
    mt_geometry *g = b->g;
    prim *p = b->p + t->start;
    uint32_t n = t->end - t->start, i, nquad = 0, mid;
    box bb, cb;
    mt__bvh_ref *ref, node_ref;
    double area;
    int a;
    split s;

    box_empty(&bb);
    box_empty(&cb);
    for (i = 0; i < n; ++i) {
        box_add(&bb, p[i].lo, p[i].hi);
        box_add(&cb, p[i].c, p[i].c);
        nquad += p[i].quad != 0;
    }
    if (t->parent < 0) {
        for (a = 0; a < 3; ++a) {
            g->root_box[2 * a] = bb.lo[a];
            g->root_box[2 * a + 1] = bb.hi[a];
        }
        ref = &g->root;
    } else {
        mt__bvh_node *pn = &g->nodes[t->parent];
        for (a = 0; a < 3; ++a) {
            pn->b[2 * a][t->slot] = bb.lo[a];
            pn->b[2 * a + 1][t->slot] = bb.hi[a];
        }
        ref = &pn->c[t->slot];
    }
    if (t->depth > g->stats.max_depth) g->stats.max_depth = t->depth;
    area = box_area(&bb);

    s.axis = -1;
    s.cost = 1e300;
    if (n > 1 && t->depth < MT__BVH_SAH_DEPTH && area > 0) s = find_split(p, n, &cb, area);
    if (n == 1 || (n <= MT__BVH_LEAF_MAX && (nquad == 0 || nquad == n) && s.cost >= n)) {
        emit_leaf(b, t, ref);
        b->g->stats.sah_cost += area > 0 && b->root_area > 0 ? n * area / b->root_area : 0;
        return MT_OK;
    }
    if (n <= MT__BVH_LEAF_MAX && nquad > 0 && nquad < n) {
        mid = partition_kind(p, n);
    } else if (s.axis >= 0) {
        mid = partition_bins(p, n, s.axis, s.bin, &cb);
    } else {
        /* no useful plane (coincident centroids, or too deep for the SAH):
         * halve at the median of the widest centroid extent */
        int w = 0;
        for (a = 1; a < 3; ++a)
            if (cb.hi[a] - cb.lo[a] > cb.hi[w] - cb.lo[w]) w = a;
        mid = n / 2;
        if (cb.hi[w] > cb.lo[w]) nth_element(p, n, mid, w);
    }
    if (mid == 0 || mid == n) mid = n / 2; /* cannot happen; keeps the recursion finite */

    node_ref.index = g->nnodes++;
    node_ref.count = 0;
    node_ref.kind = 0;
    *ref = node_ref;
    g->stats.inner_nodes++;
    if (b->root_area > 0) g->stats.sah_cost += MT__BVH_TRAVERSAL_COST * area / b->root_area;
    /* the right half is pushed first so that the left is built next and
     * its node follows this one */
    if (push(b, t->start + mid, t->end, t->depth + 1, (int32_t)node_ref.index, 1, err) != MT_OK ||
        push(b, t->start, t->start + mid, t->depth + 1, (int32_t)node_ref.index, 0, err) != MT_OK)
        return MT_ERR_NOMEM;
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
    g->tri = mt__malloc(((size_t)ntri * 9 + 1) * sizeof *g->tri);
    g->tri_id = mt__malloc(((size_t)ntri + 1) * sizeof *g->tri_id);
    g->quad = mt__malloc(((size_t)nquad + 1) * sizeof *g->quad);
    g->quad_id = mt__malloc(((size_t)nquad + 1) * sizeof *g->quad_id);
    /* at most total - 1 inner nodes; 64-byte alignment for the cache lines */
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
    g->root.index = 0;
    g->root.count = 0;
    g->root.kind = 0;
    if (total == 0) return MT_OK;
    if ((st = gather(&b, err)) == MT_OK) {
        box rb;
        uint32_t i;
        box_empty(&rb);
        for (i = 0; i < total; ++i) box_add(&rb, b.p[i].lo, b.p[i].hi);
        b.root_area = box_area(&rb);
        st = push(&b, 0, total, 0, -1, 0, err);
        while (st == MT_OK && b.nstack > 0) {
            task t = b.stack[--b.nstack];
            st = build_task(&b, &t, err);
        }
    }
    mt__free(b.p);
    mt__free(b.stack);
    if (st != MT_OK) {
        mt__bvh_free(g);
        return st;
    }
    g->stats.prims = total;
    g->stats.bytes = g->nnodes * sizeof *g->nodes + g->ntri * (9 * sizeof(mt_real) + 4) +
                     g->nquad * (sizeof(void *) + 4);
    return MT_OK;
}
