/*
 * Internal: pbrt-v2's point k-d tree (core/kdtree.h), which the irregular
 * measured BRDF searches for the samples near a remapped direction pair.
 *
 * Build (KdTree::recursiveBuild): a node per point; a node's points are split
 * on the axis of greatest extent of their bounding box at the median, the
 * point of rank (start + end) / 2 in the order "coordinate, then original
 * index" (pbrt-v2 breaks ties by the points' addresses in its input array,
 * which is the same order), and that point is stored in the node. Nodes are
 * numbered depth first: the left child follows its parent, the right child
 * takes the next free number after the left subtree. The tree is therefore
 * the same as pbrt-v2's, whatever selection algorithm finds the medians.
 *
 * Lookup (KdTree::privateLookup): children first, the side of the split that
 * holds the query point, then the other side if the squared distance to the
 * splitting plane is below *max_d2; then the node's own point, handed to the
 * callback if its squared distance is below *max_d2 (strictly). The callback
 * may shrink *max_d2. Visiting in pbrt-v2's order keeps its sums' rounding.
 */
#ifndef MT_CORE_KDTREE_H
#define MT_CORE_KDTREE_H

#include <stdint.h>
#include "materia/error.h"

typedef struct mt__kdnode {
    mt_real p[3];     /* the node's point */
    mt_real split;    /* the split position on axis (interior nodes) */
    uint32_t right;   /* the right child's number, or MT__KD_NONE */
    int32_t item;     /* the point's index in the build input */
    uint8_t axis;     /* 0, 1, 2; 3 for a leaf */
    uint8_t has_left; /* the left child is node number + 1 */
} mt__kdnode;

#define MT__KD_NONE UINT32_MAX

struct mt__kdgrid;

typedef struct mt__kdtree {
    mt__kdnode *nodes;
    int n;
    struct mt__kdgrid *grid; /* mt__kdtree_index's, or NULL */
} mt__kdtree;

/* Builds the tree of the n points (x, y, z triples; finite). n may be 0 (an
 * empty tree). MT_ERR_NOMEM with err filled when memory is exhausted. */
mt_status mt__kdtree_build(mt__kdtree *t, const mt_real *points, int n, mt_error *err);
void mt__kdtree_free(mt__kdtree *t);

/* Called for each point within the search radius: its index in the build
 * input and its squared distance to the query point. */
typedef void (*mt__kdtree_proc)(void *ctx, int item, mt_real d2, mt_real *max_d2);

void mt__kdtree_lookup(const mt__kdtree *t, const mt_real p[3], mt__kdtree_proc proc, void *ctx,
                       mt_real *max_d2);

/* pbrt-v2 DistanceSquared(node point, p), the one formula both searches use
 * (so that they agree to the bit). */
static inline mt_real mt__kd_d2(const mt_real a[3], const mt_real p[3])
{
    mt_real dx = a[0] - p[0], dy = a[1] - p[1], dz = a[2] - p[2];
    return dx * dx + dy * dy + dz * dz;
}

/* A ball search: the points with squared distance below a radius (strictly),
 * as mt__kdtree_ball finds them; mt__kdball_select then gives those within
 * any smaller radius in the tree's visiting order. */
#define MT__KDBALL_MAX 64
typedef struct mt__kdball {
    int n;       /* how many, or -1 when more than cap lie within */
    int cap;
    int ordered; /* id[] holds build indices in visiting order (the tree
                    answered), else node numbers in no particular order */
    uint32_t id[MT__KDBALL_MAX + 1];
    mt_real d2[MT__KDBALL_MAX + 1];
} mt__kdball;

/* Finds the points within max_d2 of p, at most cap (<= MT__KDBALL_MAX) of
 * them (cap < 0 counts as 0). Answered from the index of mt__kdtree_index when it covers max_d2
 * and p is finite, else by the tree; the answers are the same bits. */
void mt__kdtree_ball(const mt__kdtree *t, const mt_real p[3], mt_real max_d2, int cap,
                     mt__kdball *b);

/* How many of b's points lie within max_d2 (at most b's radius). */
static inline int mt__kdball_count(const mt__kdball *b, mt_real max_d2)
{
    int i, n = 0;
    for (i = 0; i < b->n; ++i) n += b->d2[i] < max_d2;
    return n;
}

/* b's points within max_d2 (at most b's radius; b->n >= 0) in the order in
 * which mt__kdtree_lookup hands them to a callback that leaves its radius
 * alone: their build indices in item[] and squared distances in d2[].
 * Returns how many. Only the points selected are put in order, so a caller
 * that needs one of several radii pays for the order of that one. */
int mt__kdball_select(const mt__kdtree *t, const mt_real p[3], const mt__kdball *b,
                      mt_real max_d2, int32_t *item, mt_real *d2);

/* Builds an index (kdball.c) for mt__kdtree_ball's searches of squared radius
 * up to max_d2: a uniform grid of the points, and each node's parent and
 * depth, from which the tree's visiting order is recovered. A tree deeper
 * than 31 levels or of more than 2^24 points, one with a coordinate that is
 * not finite, one whose grid would need cells of more than 64 radii (a point
 * far from the rest), or a radius that is 0 or not finite, gets no index
 * (the tree answers). MT_ERR_NOMEM with err filled when memory is exhausted. */
mt_status mt__kdtree_index(mt__kdtree *t, mt_real max_d2, mt_error *err);
void mt__kdtree_index_free(mt__kdtree *t);

#endif
