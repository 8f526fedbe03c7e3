/*
 * Internal: pbrt-v2's lights (lights/point.cpp, spot.cpp, distant.cpp,
 * infinite.cpp, diffuse.cpp): creation from LightSource parameters with
 * pbrt-v2's names and defaults, Sample_L towards a point, Pdf, and the
 * radiance of area lights (L) and infinite lights (Le).
 */
#ifndef MT_TRACER_LIGHT_H
#define MT_TRACER_LIGHT_H

#include "materia/mipmap.h"
#include "tracer/distrib.h"
#include "tracer/geometry.h"

typedef enum mt__light_kind {
    MT__LIGHT_POINT,
    MT__LIGHT_SPOT,
    MT__LIGHT_DISTANT,
    MT__LIGHT_INFINITE,
    MT__LIGHT_AREA
} mt__light_kind;

typedef struct mt__light {
    mt__light_kind kind;
    int nsamples;           /* pbrt-v2's "nsamples" (area and infinite lights; 1 otherwise) */
    mt_rgb L;               /* point, spot: intensity I; distant, area: radiance; infinite:
                               the constant L (scale applied) */
    mt_vec3 pos;            /* point, spot */
    mt_vec3 dir;            /* distant: unit direction towards the light */
    mt_transform w2l, l2w;  /* spot (direction to +z) and infinite lights */
    mt_real w2l3[3][3], l2w3[3][3]; /* their linear parts rounded to mt_real */
    mt_real cos_total, cos_falloff; /* spot */
    mt_mipmap *map;         /* infinite with a mapname: the map times L (owned) */
    mt__distrib2d distrib;  /* infinite: pbrt-v2's sampling distribution (1x1 when constant) */
    const mt_shape *shape;  /* area */
} mt__light;

/* A light from a LightSource statement of type `type` with parameters ps
 * (marked used) under light-to-world l2w. "point", "spot", "distant",
 * "infinite"; pbrt-v2's "goniometric" and "projection" are
 * MT_ERR_UNSUPPORTED; a map that cannot be read is an error. */
mt_status mt__light_create(mt__light *l, const char *type, const mt_paramset *ps,
                           const mt_transform *l2w, mt_mode mode, mt_error *err);
/* A diffuse area light ("area" or "diffuse": L, scale, nsamples) on shape. */
mt_status mt__area_light_create(mt__light *l, const char *type, const mt_paramset *ps,
                                const mt_shape *shape, mt_error *err);
void mt__light_free(mt__light *l);

static inline int mt__light_is_delta(const mt__light *l)
{
    return l->kind == MT__LIGHT_POINT || l->kind == MT__LIGHT_SPOT || l->kind == MT__LIGHT_DISTANT;
}

/* Sample_L from the point p (on the surface sf, or sf NULL for a free point):
 * the incident radiance Li along wi (unit, towards the light), its pdf (solid
 * angle; 1 for delta lights) and the shadow ray that must be unoccluded.
 * Li is black or pdf 0 when the sample contributes nothing. */
typedef struct mt__light_sample {
    mt_rgb Li;
    mt_vec3 wi;
    mt_real pdf;
    /* pdf is the light's Pdf(p, w) for every direction w from p (a sphere's
     * cone): mt__light_pdf at p need not be asked again */
    int pdf_any_dir;
    mt_ray shadow;
} mt__light_sample;

void mt__light_sample_l(const mt__light *l, const mt_surface *sf, mt_vec3 p, mt_real ucomp,
                        mt_real u1, mt_real u2, mt__light_sample *out);
/* Pdf(p, wi) (wi unit): 0 for delta lights. */
mt_real mt__light_pdf(const mt__light *l, mt_vec3 p, mt_vec3 wi);
/* An area light's radiance leaving a point with normal n in direction w. */
static inline mt_rgb mt__area_light_l(const mt__light *l, mt_vec3 n, mt_vec3 w)
{
    return mt_v3_dot(n, w) > 0 ? l->L : mt_rgb_black();
}
/* Le(ray) of a ray with direction d that leaves the scene (infinite lights;
 * black for the others). */
mt_rgb mt__light_le(const mt__light *l, mt_vec3 d);

/* A direction through a linear part (w2l3, l2w3). */
static inline mt_vec3 mt__m3_apply(const mt_real m[3][3], mt_vec3 v)
{
    return mt_v3(m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
                 m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
                 m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z);
}

/* Infinite lights (light_infinite.c). */
mt_status mt__infinite_init(mt__light *l, const char *mapname, mt_mode mode, mt_error *err);
void mt__infinite_sample(const mt__light *l, mt_real u1, mt_real u2, mt_vec3 *wi, mt_real *pdf,
                         mt_rgb *Li);
mt_real mt__infinite_pdf(const mt__light *l, mt_vec3 wi);
mt_rgb mt__infinite_le(const mt__light *l, mt_vec3 d);

#endif
