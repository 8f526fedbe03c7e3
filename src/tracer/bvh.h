/*
 * Internal: the geometry record and its BVH.
 *
 * The BVH is four-wide (Dammertz et al., "Shallow Bounding Volume
 * Hierarchies for Fast SIMD Ray Tracing of Incoherent Rays", 2008; Embree's
 * BVH4): each node holds the bounding boxes of its up to four children in
 * structure-of-arrays form, so that one visit tests four boxes with the same
 * arithmetic in four lanes, and the nodes are stored depth-first in one
 * array. Leaves hold up to MT__BVH_LEAF_MAX primitives of one kind:
 * triangles, copied in packets of four in structure-of-arrays form (vertex,
 * coordinate, lane: 36 reals; unused lanes hold NaN and never hit) so that
 * four are tested at once, or quadrics (the shape pointer).
 */
#ifndef MT_TRACER_BVH_H
#define MT_TRACER_BVH_H

#include "tracer/shape_impl.h"

#define MT__BVH_LEAF_MAX 8
/* Depth (in four-wide levels) at which the builder stops using the SAH and
 * splits at the median; each later level at least halves the largest range,
 * so the tree is at most 24 + 32 levels deep and the traversal stack (at
 * most 3 entries per level) never overflows. */
#define MT__BVH_SAH_DEPTH 24
#define MT__BVH_STACK 192

enum { MT__LEAF_TRIS = 1, MT__LEAF_QUADRICS = 2 };

/* A child: an inner node (count 0, index into nodes) or a leaf (count
 * primitives of kind from index on in the leaf arrays of that kind; for
 * triangles index is the first packet). */
typedef struct mt__bvh_ref {
    uint32_t index;
    uint16_t count;
    uint16_t kind;
} mt__bvh_ref;

typedef struct mt__bvh_node {
    /* rows lo.x, hi.x, lo.y, hi.y, lo.z, hi.z; columns: the four children
     * (an empty slot has lo = +max > hi = -max and is never entered) */
    mt_real b[6][4];
    mt__bvh_ref c[4]; /* float build: 128 bytes, two cache lines */
} mt__bvh_node;

/* Four triangles: v[vertex][coordinate][lane]. */
typedef struct mt__tri4 {
    mt_real v[3][3][4];
} mt__tri4;

struct mt_geometry {
    mt_shape **shapes;
    uint32_t nshapes, cap;
    uint32_t *base; /* first global primitive id of each shape; base[nshapes] = total */
    int committed;

    mt__bvh_node *nodes;
    void *nodes_mem; /* nodes, before alignment */
    uint32_t nnodes;
    mt__bvh_ref root;
    mt_real root_box[6]; /* lo.x, hi.x, lo.y, hi.y, lo.z, hi.z */
    mt__bvh_node root_node; /* the root box in its first lane, for the first test */

    mt__tri4 *tri;     /* triangle packets, in leaf order */
    uint32_t *tri_id;  /* global primitive ids, 4 per packet (padding: UINT32_MAX) */
    uint32_t ntri;     /* packets */
    const mt_shape **quad; /* quadric shapes, in leaf order */
    uint32_t *quad_id;
    uint32_t nquad;
    mt_bvh_stats stats;
};

/* Builds the BVH of g's shapes (bvh_build.c). */
mt_status mt__bvh_build(mt_geometry *g, mt_error *err);
void mt__bvh_free(mt_geometry *g);

#endif
