/*
 * pbrt-v2's point k-d tree (core/kdtree.h): see kdtree.h for the build and
 * lookup rules this keeps. pbrt-v2 finds each median with std::nth_element;
 * here a quickselect (median-of-three pivots, heapsort when a range refuses
 * to shrink) does it. Because the order is total (ties broken by index), the
 * median and the two halves are the same whatever the algorithm.
 */
#include "core/kdtree.h"
#include "core/alloc.h"

typedef struct kd_builder {
    mt__kdtree *t;
    const mt_real *pts;
    int32_t *idx;
    uint32_t next_free;
} kd_builder;

/* pbrt-v2 CompareNode: by the coordinate on axis, then by input position. */
static int less(const mt_real *pts, int axis, int32_t a, int32_t b)
{
    mt_real pa = pts[3 * a + axis], pb = pts[3 * b + axis];
    return pa < pb || (pa == pb && a < b);
}

static void swap(int32_t *a, int i, int j)
{
    int32_t t = a[i];
    a[i] = a[j];
    a[j] = t;
}

static void sift_down(const mt_real *pts, int axis, int32_t *a, int root, int n)
{
    for (;;) {
        int child = 2 * root + 1;
        if (child >= n) return;
        if (child + 1 < n && less(pts, axis, a[child], a[child + 1])) child++;
        if (!less(pts, axis, a[root], a[child])) return;
        swap(a, root, child);
        root = child;
    }
}

static void heap_sort(const mt_real *pts, int axis, int32_t *a, int n)
{
    int i;
    for (i = n / 2 - 1; i >= 0; --i) sift_down(pts, axis, a, i, n);
    for (i = n - 1; i > 0; --i) {
        swap(a, 0, i);
        sift_down(pts, axis, a, 0, i);
    }
}

/* Rearranges a[lo, hi) so that a[k] holds the element of rank k - lo, with
 * the smaller ones before it and the greater ones after (nth_element). */
static void select_kth(const mt_real *pts, int axis, int32_t *a, int lo, int hi, int k)
{
    int rounds = 0, limit = 8, n;
    for (n = hi - lo; n > 1; n >>= 1) limit += 2; /* 2 log2(n) + 8 */
    while (hi - lo > 2) {
        int mid = lo + (hi - lo) / 2, last = hi - 1, m, store, i;
        if (++rounds > limit) { /* adversarial order: finish in n log n */
            heap_sort(pts, axis, a + lo, hi - lo);
            return;
        }
        /* the median of a[lo], a[mid], a[last] becomes the pivot, at last */
        if (less(pts, axis, a[lo], a[mid]))
            m = less(pts, axis, a[mid], a[last]) ? mid : (less(pts, axis, a[lo], a[last]) ? last : lo);
        else
            m = less(pts, axis, a[lo], a[last]) ? lo : (less(pts, axis, a[mid], a[last]) ? last : mid);
        swap(a, m, last);
        for (store = lo, i = lo; i < last; ++i)
            if (less(pts, axis, a[i], a[last])) swap(a, i, store++);
        swap(a, store, last);
        if (k == store) return;
        if (k < store)
            hi = store;
        else
            lo = store + 1;
    }
    if (hi - lo == 2 && less(pts, axis, a[lo + 1], a[lo])) swap(a, lo, lo + 1);
}

static void set_point(mt__kdnode *nd, const mt_real *pts, int32_t item)
{
    nd->p[0] = pts[3 * item];
    nd->p[1] = pts[3 * item + 1];
    nd->p[2] = pts[3 * item + 2];
    nd->item = item;
    nd->right = MT__KD_NONE;
    nd->has_left = 0;
    nd->split = 0;
}

/* pbrt-v2 KdTree::recursiveBuild for the points idx[start, end). */
static void build(kd_builder *b, uint32_t num, int start, int end)
{
    mt__kdnode *nd = &b->t->nodes[num];
    mt_real lo[3], hi[3];
    int i, c, axis, mid;
    if (start + 1 == end) {
        set_point(nd, b->pts, b->idx[start]);
        nd->axis = 3;
        return;
    }
    /* pbrt-v2 BBox of the points and BBox::MaximumExtent */
    for (c = 0; c < 3; ++c) {
        lo[c] = (mt_real)INFINITY;
        hi[c] = -(mt_real)INFINITY;
    }
    for (i = start; i < end; ++i)
        for (c = 0; c < 3; ++c) {
            mt_real v = b->pts[3 * b->idx[i] + c];
            lo[c] = mt_min(lo[c], v);
            hi[c] = mt_max(hi[c], v);
        }
    {
        mt_real dx = hi[0] - lo[0], dy = hi[1] - lo[1], dz = hi[2] - lo[2];
        axis = (dx > dy && dx > dz) ? 0 : (dy > dz ? 1 : 2);
    }
    mid = (start + end) / 2;
    select_kth(b->pts, axis, b->idx, start, end, mid);
    set_point(nd, b->pts, b->idx[mid]);
    nd->axis = (uint8_t)axis;
    nd->split = nd->p[axis];
    if (start < mid) {
        nd->has_left = 1;
        build(b, b->next_free++, start, mid);
    }
    if (mid + 1 < end) {
        nd->right = b->next_free++;
        build(b, nd->right, mid + 1, end);
    }
}

mt_status mt__kdtree_build(mt__kdtree *t, const mt_real *points, int n, mt_error *err)
{
    kd_builder b;
    int i;
    t->nodes = NULL;
    t->n = 0;
    t->grid = NULL;
    if (n <= 0) return MT_OK;
    t->nodes = mt__malloc((size_t)n * sizeof *t->nodes);
    b.idx = mt__malloc((size_t)n * sizeof *b.idx);
    if (!t->nodes || !b.idx) {
        mt__free(t->nodes);
        mt__free(b.idx);
        t->nodes = NULL;
        return mt_error_set(err, MT_ERR_NOMEM, "out of memory building a k-d tree of %d points", n);
    }
    for (i = 0; i < n; ++i) b.idx[i] = i;
    b.t = t;
    b.pts = points;
    b.next_free = 1;
    t->n = n;
    build(&b, 0, 0, n);
    mt__free(b.idx);
    return MT_OK;
}

void mt__kdtree_free(mt__kdtree *t)
{
    mt__kdtree_index_free(t);
    mt__free(t->nodes);
    t->nodes = NULL;
    t->n = 0;
}

static void lookup(const mt__kdtree *t, uint32_t num, const mt_real p[3], mt__kdtree_proc proc,
                   void *ctx, mt_real *max_d2)
{
    const mt__kdnode *nd = &t->nodes[num];
    mt_real d2;
    if (nd->axis != 3) {
        mt_real d = p[nd->axis] - nd->split, plane2 = d * d;
        if (p[nd->axis] <= nd->split) {
            if (nd->has_left) lookup(t, num + 1, p, proc, ctx, max_d2);
            if (plane2 < *max_d2 && nd->right != MT__KD_NONE)
                lookup(t, nd->right, p, proc, ctx, max_d2);
        } else {
            if (nd->right != MT__KD_NONE) lookup(t, nd->right, p, proc, ctx, max_d2);
            if (plane2 < *max_d2 && nd->has_left) lookup(t, num + 1, p, proc, ctx, max_d2);
        }
    }
    d2 = mt__kd_d2(nd->p, p);
    if (d2 < *max_d2) proc(ctx, nd->item, d2, max_d2);
}

void mt__kdtree_lookup(const mt__kdtree *t, const mt_real p[3], mt__kdtree_proc proc, void *ctx,
                       mt_real *max_d2)
{
    if (t->n > 0) lookup(t, 0, p, proc, ctx, max_d2);
}
