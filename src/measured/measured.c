/*
 * Measured BRDF data: the reference-counted object behind both measured
 * BxDFs, made from memory or by the file readers (brdf_file.c, merl_file.c).
 */
#include "measured/measured_impl.h"
#include "core/alloc.h"

const float mt__merl_scale[3] = {1.f / 1500.f, 1.15f / 1500.f, 1.66f / 1500.f};

static mt_measured *new_data(mt_measured_kind kind, int n, mt_error *err)
{
    mt_measured *m = mt__calloc(1, sizeof *m);
    if (!m) {
        mt_error_set(err, MT_ERR_NOMEM, "out of memory creating measured BRDF data");
        return NULL;
    }
    m->refs = 1;
    m->kind = kind;
    m->n = n;
    return m;
}

mt_measured *mt__measured_irregular(mt_real *points, mt_rgb *values, int n, mt_error *err)
{
    mt_measured *m = new_data(MT_MEASURED_IRREGULAR, n, err);
    if (!m) {
        mt__free(points);
        mt__free(values);
        return NULL;
    }
    m->points = points;
    m->values = values;
    /* the first search of IrregIsotropicBRDF::f is answered from the grid */
    if (mt__kdtree_build(&m->tree, points, n, err) != MT_OK ||
        mt__kdtree_index(&m->tree, MT__IRREG_WIDE_D2, err) != MT_OK) {
        mt_measured_destroy(m);
        return NULL;
    }
    return m;
}

mt_measured *mt__measured_halfangle(mt_real *table, mt_error *err)
{
    mt_measured *m = new_data(MT_MEASURED_HALFANGLE, MT_MERL_SAMPLES, err);
    if (!m) {
        mt__free(table);
        return NULL;
    }
    m->table = table;
    return m;
}

mt_measured *mt_measured_irregular_create(const mt_vec3 *wo, const mt_vec3 *wi,
                                          const mt_rgb *values, int n, mt_error *err)
{
    mt_real *pts;
    mt_rgb *vals;
    int i;
    mt_error_clear(err);
    if (!wo || !wi || !values || n < 1) {
        mt_error_set(err, MT_ERR_INVALID, "irregular measured BRDF: no samples");
        return NULL;
    }
    for (i = 0; i < n; ++i)
        if (!mt_v3_is_finite(wo[i]) || !mt_v3_is_finite(wi[i]) || !mt_rgb_is_finite(values[i])) {
            mt_error_set(err, MT_ERR_INVALID,
                         "irregular measured BRDF: sample %d has a value that is not finite", i);
            return NULL;
        }
    pts = mt__malloc((size_t)n * 3 * sizeof *pts);
    vals = mt__malloc((size_t)n * sizeof *vals);
    if (!pts || !vals) {
        mt__free(pts);
        mt__free(vals);
        mt_error_set(err, MT_ERR_NOMEM, "out of memory creating measured BRDF data");
        return NULL;
    }
    for (i = 0; i < n; ++i) {
        mt_vec3 p = mt_brdf_remap(wo[i], wi[i]);
        pts[3 * i] = p.x;
        pts[3 * i + 1] = p.y;
        pts[3 * i + 2] = p.z;
        vals[i] = values[i];
    }
    return mt__measured_irregular(pts, vals, n, err);
}

mt_measured *mt_measured_halfangle_create(const mt_real *rgb, mt_error *err)
{
    size_t k, n = 3 * (size_t)MT_MERL_SAMPLES;
    mt_real *table;
    mt_error_clear(err);
    if (!rgb) {
        mt_error_set(err, MT_ERR_INVALID, "half-angle measured BRDF: no table");
        return NULL;
    }
    for (k = 0; k < n; ++k)
        if (!mt_is_finite(rgb[k]) || rgb[k] < 0) {
            mt_error_set(err, MT_ERR_INVALID,
                         "half-angle measured BRDF: entry %lu channel %lu is %g (not a finite "
                         "value >= 0)", (unsigned long)(k / 3), (unsigned long)(k % 3),
                         (double)rgb[k]);
            return NULL;
        }
    table = mt__malloc(n * sizeof *table);
    if (!table) {
        mt_error_set(err, MT_ERR_NOMEM, "out of memory creating measured BRDF data");
        return NULL;
    }
    for (k = 0; k < n; ++k) table[k] = rgb[k];
    return mt__measured_halfangle(table, err);
}

mt_measured *mt_measured_retain(mt_measured *m)
{
    if (m) __atomic_add_fetch(&m->refs, 1, __ATOMIC_RELAXED);
    return m;
}

void mt_measured_destroy(mt_measured *m)
{
    if (!m || __atomic_sub_fetch(&m->refs, 1, __ATOMIC_ACQ_REL) != 0) return;
    mt__kdtree_free(&m->tree);
    mt__free(m->points);
    mt__free(m->values);
    mt__free(m->table);
    mt__free(m);
}

mt_measured_kind mt_measured_kind_of(const mt_measured *m) { return m->kind; }
int mt_measured_count(const mt_measured *m) { return m->n; }
const mt_real *mt_measured_table(const mt_measured *m) { return m->table; }

int mt_measured_sample(const mt_measured *m, int i, mt_vec3 *point, mt_rgb *value)
{
    if (m->kind != MT_MEASURED_IRREGULAR || i < 0 || i >= m->n) return 0;
    if (point) *point = mt_v3(m->points[3 * i], m->points[3 * i + 1], m->points[3 * i + 2]);
    if (value) *value = m->values[i];
    return 1;
}
