/*
 * Ball searches of pbrt-v2's point k-d tree answered from a uniform grid.
 *
 * The irregular measured BRDF asks for the samples within a small radius of
 * a point, in the order in which pbrt-v2's KdTree::privateLookup visits them,
 * because that order decides the rounding of its weighted sums. The tree
 * search spends most of its time on data-dependent branches (about 68 nodes
 * visited for 12 samples found in the measured scene). Here the candidates
 * come from the grid cells that the ball's bounding box overlaps, with the
 * tree's own squared distance, and the visiting order is recovered from the
 * tree's shape afterwards:
 *
 * the search is a post-order walk in which each interior node sends it first
 * to the child on the query's side of its split (p[axis] <= split: left).
 * Write a node's path from the root as one digit per level, 0 when it goes
 * to the side visited first and 1 for the other, and end it with a 2. Two
 * nodes then come in the order of these digit strings: where they first
 * differ, either both go on (0 before 1: the first-visited subtree first) or
 * one ends (a 2: the other is its descendant, which post-order puts first).
 * Two bits a level and the key fits a 64-bit integer for trees of up to 31
 * levels. A subtree that the tree search skips holds no point within the
 * radius (kdtree.h), so skipping is invisible in the order.
 */
#include <math.h>
#include <string.h>
#include "core/kdtree.h"
#include "core/alloc.h"

#define MAX_LEVELS 31

/* What the order key needs of a node's parent, in one load: the parent's
 * split and, packed, its number, the node's depth, the parent's axis and
 * whether the node is its right child. */
typedef struct mt__kdedge {
    mt_real split;
    uint32_t up; /* parent << 8 | depth << 3 | axis << 1 | right */
} mt__kdedge;

struct mt__kdgrid {
    mt_real max_d2;      /* the largest squared radius served */
    mt_real lo[3], inv[3]; /* cell of x on axis c: floor((x - lo[c]) * inv[c]) */
    int dim[3];
    uint32_t *start;     /* points of cell k: start[k] .. start[k + 1] - 1 */
    mt_real *xyz;        /* the points by cell (3 each), node order within a cell */
    uint32_t *node;      /* their node numbers */
    mt__kdedge *edge;    /* each node's link to its parent (the root's unused) */
};

/* Monotonic in x (a subtraction and a product by a positive constant, both
 * rounded, then floor), so a point inside [a, b] falls in a cell between
 * those of a and b, whatever the rounding; NaN goes to cell 0. */
static int ball_cell_of(const struct mt__kdgrid *g, int c, mt_real x)
{
    mt_real v = (x - g->lo[c]) * g->inv[c];
    if (!(v >= 0)) return 0;
    if (v >= (mt_real)g->dim[c]) return g->dim[c] - 1;
    return (int)v;
}

void mt__kdtree_index_free(mt__kdtree *t)
{
    struct mt__kdgrid *g = t->grid;
    if (!g) return;
    mt__free(g->start);
    mt__free(g->xyz);
    mt__free(g->node);
    mt__free(g->edge);
    mt__free(g);
    t->grid = NULL;
}

/* Cells of the radius (the ball's box spans 2 to 3 an axis). Smaller cells
 * give fewer candidates but more rows to start: with mystique.brdf, cells
 * of a quarter to two radii, alike or not along the axes, were within 10%
 * of each other in bench/measured, this one at the best end. The cells grow
 * until there are at most 8 a point (4096 at least) and 1024 an axis. */
static double grid_shape(struct mt__kdgrid *g, const mt_real hi[3], mt_real radius, int n)
{
    static const double share[3] = {1, 1, 1};
    double scale = (double)radius, limit = 8.0 * n + 4096;
    int c;
    for (;;) {
        double total = 1;
        int ok = 1;
        for (c = 0; c < 3; ++c) {
            double cells = floor(((double)hi[c] - (double)g->lo[c]) / (share[c] * scale)) + 1;
            if (cells > 1024) ok = 0;
            total *= cells;
            g->dim[c] = (int)fmin(cells, 1024);
        }
        if (ok && total <= limit) break;
        scale *= 1.25;
    }
    for (c = 0; c < 3; ++c) g->inv[c] = (mt_real)(1.0 / (share[c] * scale));
    return scale;
}

mt_status mt__kdtree_index(mt__kdtree *t, mt_real max_d2, mt_error *err)
{
    struct mt__kdgrid *g;
    mt_real lo3[3], hi[3];
    size_t cells;
    uint32_t v, *fill;
    uint8_t *depth;
    int c, i;
    mt__kdtree_index_free(t);
    /* node numbers share 24 bits with the depth and axis (mt__kdedge) */
    if (t->n <= 0 || t->n > (1 << 24) || !(max_d2 > 0) || !isfinite(max_d2)) return MT_OK;
    /* the grid spans the points' box: where a coordinate is not finite (an
     * extent of inf or NaN) no grid of finite cells covers it; the tree answers */
    for (c = 0; c < 3; ++c) lo3[c] = hi[c] = t->nodes[0].p[c];
    for (i = 0; i < t->n; ++i)
        for (c = 0; c < 3; ++c) {
            if (!isfinite(t->nodes[i].p[c])) return MT_OK;
            lo3[c] = mt_min(lo3[c], t->nodes[i].p[c]);
            hi[c] = mt_max(hi[c], t->nodes[i].p[c]);
        }
    for (c = 0; c < 3; ++c)
        if (!isfinite(hi[c] - lo3[c])) return MT_OK;
    g = mt__calloc(1, sizeof *g);
    if (!g) goto nomem;
    t->grid = g;
    g->max_d2 = max_d2;
    g->edge = mt__malloc((size_t)t->n * sizeof *g->edge);
    depth = mt__malloc((size_t)t->n);
    if (!g->edge || !depth) {
        mt__free(depth);
        goto nomem;
    }
    /* nodes are numbered depth first, so a parent comes before its children */
    depth[0] = 0;
    g->edge[0].split = 0;
    g->edge[0].up = 0;
    for (v = 0; v < (uint32_t)t->n; ++v) {
        const mt__kdnode *nd = &t->nodes[v];
        if (depth[v] >= MAX_LEVELS) { /* keys would not fit: the tree answers */
            mt__free(depth);
            mt__kdtree_index_free(t);
            return MT_OK;
        }
        if (nd->has_left) {
            g->edge[v + 1].split = nd->split;
            g->edge[v + 1].up = v << 8 | (uint32_t)(depth[v] + 1) << 3 | (uint32_t)nd->axis << 1;
            depth[v + 1] = (uint8_t)(depth[v] + 1);
        }
        if (nd->right != MT__KD_NONE) {
            g->edge[nd->right].split = nd->split;
            g->edge[nd->right].up = v << 8 | (uint32_t)(depth[v] + 1) << 3 | (uint32_t)nd->axis << 1 | 1;
            depth[nd->right] = (uint8_t)(depth[v] + 1);
        }
    }
    mt__free(depth);
    for (c = 0; c < 3; ++c) g->lo[c] = lo3[c];
    /* a point far from the rest stretches the cells until the others share
     * a few of them, and each search would scan them all: the tree answers */
    if (grid_shape(g, hi, mt_sqrt(max_d2), t->n) > 64.0 * (double)mt_sqrt(max_d2)) {
        mt__kdtree_index_free(t);
        return MT_OK;
    }
    cells = (size_t)g->dim[0] * (size_t)g->dim[1] * (size_t)g->dim[2];
    g->start = mt__calloc(cells + 1, sizeof *g->start);
    g->xyz = mt__malloc((size_t)t->n * 3 * sizeof *g->xyz);
    g->node = mt__malloc((size_t)t->n * sizeof *g->node);
    fill = mt__malloc((cells + 1) * sizeof *fill);
    if (!g->start || !g->xyz || !g->node || !fill) {
        mt__free(fill);
        goto nomem;
    }
    /* counting sort of the nodes by cell, node order kept within a cell */
    for (v = 0; v < (uint32_t)t->n; ++v) {
        const mt_real *q = t->nodes[v].p;
        size_t k = ((size_t)ball_cell_of(g, 2, q[2]) * (size_t)g->dim[1] + (size_t)ball_cell_of(g, 1, q[1])) *
                       (size_t)g->dim[0] + (size_t)ball_cell_of(g, 0, q[0]);
        g->start[k + 1]++;
    }
    for (i = 0; (size_t)i < cells; ++i) g->start[i + 1] += g->start[i];
    memcpy(fill, g->start, (cells + 1) * sizeof *fill);
    for (v = 0; v < (uint32_t)t->n; ++v) {
        const mt_real *q = t->nodes[v].p;
        size_t k = ((size_t)ball_cell_of(g, 2, q[2]) * (size_t)g->dim[1] + (size_t)ball_cell_of(g, 1, q[1])) *
                       (size_t)g->dim[0] + (size_t)ball_cell_of(g, 0, q[0]);
        uint32_t at = fill[k]++;
        g->xyz[3 * at] = q[0];
        g->xyz[3 * at + 1] = q[1];
        g->xyz[3 * at + 2] = q[2];
        g->node[at] = v;
    }
    mt__free(fill);
    return MT_OK;
nomem:
    mt__kdtree_index_free(t);
    return mt_error_set(err, MT_ERR_NOMEM, "out of memory indexing a k-d tree of %d points", t->n);
}

/* The tree search's own answer (mt__kdtree_lookup with a collecting
 * callback that ends the search once more than the cap are found). */
static void collect_one(void *ctx, int item, mt_real d2, mt_real *max_d2)
{
    mt__kdball *b = ctx;
    if (b->n < 0) return;
    if (b->n == b->cap) {
        b->n = -1;
        *max_d2 = 0; /* nothing further can be of use */
        return;
    }
    b->id[b->n] = (uint32_t)item;
    b->d2[b->n++] = d2;
}

static int depth_of(const struct mt__kdgrid *g, uint32_t v) { return (int)(g->edge[v].up >> 3 & 31); }

/* The key of node v for the query p (file comment): two bits a level, 0
 * near side, 1 far side, 2 where the path ends, from the level below top
 * (the found nodes' common ancestor, whose digits above are the same for
 * all); built from the node up, each parent's digit entering at the top.
 * (The depth bounds the walk up front: a loop ended by a loaded parent
 * number would only learn of its end at the end of the chain of loads.) */
static uint64_t order_key(const struct mt__kdgrid *g, uint32_t v, int top, const mt_real p[3])
{
    uint64_t key = (uint64_t)2 << 62;
    int level = depth_of(g, v) - top;
    for (; level > 0; --level) {
        const mt__kdedge *e = &g->edge[v];
        unsigned right_first = !(p[(e->up >> 1) & 3] <= e->split);
        key = key >> 2 | (uint64_t)((e->up & 1) ^ right_first) << 62;
        v = e->up >> 8;
    }
    return key;
}

void mt__kdtree_ball(const mt__kdtree *t, const mt_real p[3], mt_real max_d2, int cap,
                     mt__kdball *b)
{
    const struct mt__kdgrid *g = t->grid;
    int lo[3], hi[3], c, y, z, n = 0;
    if (cap > MT__KDBALL_MAX) cap = MT__KDBALL_MAX;
    if (cap < 0) cap = 0;
    b->cap = cap;
    if (!g || !(max_d2 <= g->max_d2) || !isfinite(p[0]) || !isfinite(p[1]) || !isfinite(p[2])) {
        mt_real r2 = max_d2;
        b->n = 0;
        b->ordered = 1;
        mt__kdtree_lookup(t, p, collect_one, b, &r2);
        return;
    }
    b->ordered = 0;
    {
        /* a point within the radius has |q - p| < r (1 + 2^-22) on each axis,
         * exactly; the margin also covers the rounding of p -/+ m */
        mt_real r = mt_sqrt(max_d2);
        for (c = 0; c < 3; ++c) {
            mt_real m = r * (mt_real)1.001 + (mt_fabs(p[c]) + r) * (mt_real)1e-6;
            lo[c] = ball_cell_of(g, c, p[c] - m);
            hi[c] = ball_cell_of(g, c, p[c] + m);
        }
    }
    for (z = lo[2]; z <= hi[2]; ++z)
        for (y = lo[1]; y <= hi[1]; ++y) {
            size_t row = ((size_t)z * (size_t)g->dim[1] + (size_t)y) * (size_t)g->dim[0];
            uint32_t k, end = g->start[row + (size_t)hi[0] + 1];
            /* without a branch on the distance, which is taken at random:
             * every candidate is written, the count moves past it when it
             * is within (the slot is the spare one once cap is reached) */
            for (k = g->start[row + (size_t)lo[0]]; k < end; ++k) {
                mt_real e = mt__kd_d2(&g->xyz[3 * k], p);
                int at = n < cap ? n : cap;
                b->id[at] = g->node[k];
                b->d2[at] = e;
                n += e < max_d2;
            }
            if (n > cap) {
                b->n = -1;
                return;
            }
        }
    b->n = n;
}

int mt__kdball_select(const mt__kdtree *t, const mt_real p[3], const mt__kdball *b,
                      mt_real max_d2, int32_t *item, mt_real *d2)
{
    const struct mt__kdgrid *g = t->grid;
    uint64_t key[MT__KDBALL_MAX];
    uint32_t node[MT__KDBALL_MAX];
    int n = 0, i, top = 0;
    if (b->ordered) {
        for (i = 0; i < b->n; ++i)
            if (b->d2[i] < max_d2) {
                item[n] = (int32_t)b->id[i];
                d2[n++] = b->d2[i];
            }
        return n;
    }
    for (i = 0; i < b->n; ++i)
        if (b->d2[i] < max_d2) {
            node[n] = b->id[i];
            d2[n++] = b->d2[i];
        }
    if (n >= 2) {
        /* the nodes' lowest common ancestor: nodes are numbered depth first,
         * so it is the first ancestor of the largest number that is not
         * above the smallest */
        uint32_t lo_v = node[0], hi_v = node[0];
        for (i = 1; i < n; ++i) {
            lo_v = node[i] < lo_v ? node[i] : lo_v;
            hi_v = node[i] > hi_v ? node[i] : hi_v;
        }
        while (hi_v > lo_v) hi_v = g->edge[hi_v].up >> 8;
        top = depth_of(g, hi_v);
    }
    /* insertion sort by key, carrying node and distance */
    for (i = 0; i < n; ++i) {
        uint64_t kk = order_key(g, node[i], top, p);
        uint32_t v = node[i];
        mt_real e = d2[i];
        int j = i;
        while (j > 0 && key[j - 1] > kk) {
            key[j] = key[j - 1];
            node[j] = node[j - 1];
            d2[j] = d2[j - 1];
            --j;
        }
        key[j] = kk;
        node[j] = v;
        d2[j] = e;
    }
    for (i = 0; i < n; ++i) item[i] = t->nodes[node[i]].item;
    return n;
}
