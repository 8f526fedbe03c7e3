/* The scene's geometry: its shapes, their global primitive ids, commit. */
#include <string.h>
#include "core/alloc.h"
#include "tracer/bvh.h"

mt_geometry *mt_geometry_create(void)
{
    mt_geometry *g = mt__calloc(1, sizeof *g);
    if (!g) return NULL;
    g->base = mt__calloc(1, sizeof *g->base);
    if (!g->base) {
        mt__free(g);
        return NULL;
    }
    return g;
}

void mt_geometry_destroy(mt_geometry *g)
{
    uint32_t i;
    if (!g) return;
    mt__bvh_free(g);
    for (i = 0; i < g->nshapes; ++i) mt_shape_destroy(g->shapes[i]);
    mt__free(g->shapes);
    mt__free(g->base);
    mt__free(g);
}

mt_status mt_geometry_attach(mt_geometry *g, mt_shape *s, mt_error *err)
{
    uint32_t n = g->nshapes;
    if (g->committed) {
        mt_shape_destroy(s);
        return mt_error_set(err, MT_ERR_INVALID, "shape attached after mt_geometry_commit");
    }
    if ((uint64_t)g->base[n] + mt__shape_nprims(s) > (uint64_t)UINT32_MAX - 1) {
        mt_shape_destroy(s);
        return mt_error_set(err, MT_ERR_LIMIT, "more than 2^32 - 2 primitives");
    }
    if (n == g->cap) {
        uint32_t cap = g->cap ? 2 * g->cap : 16;
        mt_shape **sh = mt__realloc(g->shapes, cap * sizeof *sh);
        uint32_t *base;
        if (sh) g->shapes = sh;
        base = sh ? mt__realloc(g->base, ((size_t)cap + 1) * sizeof *base) : NULL;
        if (!base) {
            mt_shape_destroy(s);
            return mt_error_set(err, MT_ERR_NOMEM, "out of memory attaching a shape");
        }
        g->base = base;
        g->cap = cap;
    }
    g->shapes[n] = s;
    g->base[n + 1] = g->base[n] + mt__shape_nprims(s);
    g->nshapes = n + 1;
    return MT_OK;
}

mt_status mt_geometry_commit(mt_geometry *g, mt_error *err)
{
    mt_status st;
    if (g->committed) return MT_OK;
    st = mt__bvh_build(g, err);
    if (st == MT_OK) g->committed = 1;
    return st;
}

uint32_t mt_geometry_shape_count(const mt_geometry *g) { return g->nshapes; }
const mt_shape *mt_geometry_shape(const mt_geometry *g, uint32_t i) { return g->shapes[i]; }
uint32_t mt_geometry_prim_count(const mt_geometry *g) { return g->base[g->nshapes]; }

const mt_shape *mt_geometry_prim(const mt_geometry *g, uint32_t id, uint32_t *prim)
{
    /* the last shape whose base is <= id */
    uint32_t lo = 0, hi = g->nshapes;
    while (hi - lo > 1) {
        uint32_t mid = lo + (hi - lo) / 2;
        if (g->base[mid] <= id) lo = mid;
        else hi = mid;
    }
    *prim = id - g->base[lo];
    return g->shapes[lo];
}

void mt_geometry_bounds(const mt_geometry *g, mt_vec3 *lo, mt_vec3 *hi)
{
    if (!g->committed || mt_geometry_prim_count(g) == 0) {
        *lo = mt_v3(MT_REAL_MAX, MT_REAL_MAX, MT_REAL_MAX);
        *hi = mt_v3(-MT_REAL_MAX, -MT_REAL_MAX, -MT_REAL_MAX);
        return;
    }
    *lo = mt_v3(g->root_box[0], g->root_box[2], g->root_box[4]);
    *hi = mt_v3(g->root_box[1], g->root_box[3], g->root_box[5]);
}

void mt_geometry_stats(const mt_geometry *g, mt_bvh_stats *st) { *st = g->stats; }
