/*
 * pbrt-v2 Checkerboard2DTexture and Checkerboard3DTexture
 * (textures/checkerboard.h): tex1 on the checks whose integer coordinates
 * sum to an even number, tex2 on the others. The 2D texture point-samples
 * (aamode "none") or box-filters the footprint in closed form
 * ("closedform"): the fraction of [s - ds, s + ds] x [t - dt, t + dt] on
 * tex2's checks, from the integral of the odd-check indicator.
 */
#include "textures/noise.h"
#include "textures/create.h"

typedef struct checker {
    mt__pair_tex pair;
    int dim;        /* 2 or 3 */
    int closedform; /* 2D: box-filter in closed form */
    mt_map2d map2;
    mt_map3d map3;
} checker;

/* pbrt-v2's BUMPINT(x): the integral from 0 to x of the indicator of the
 * checks with odd floor (floor(x/2) + 2 max(x/2 - floor(x/2) - 1/2, 0)). */
static mt_real bumpint(mt_real x)
{
    mt_real h = x / 2, f = mt_floor(h);
    return f + 2 * mt_max(h - f - (mt_real)0.5, 0);
}

/* The box average of the odd-check indicator over [c - d, c + d] as pbrt-v2
 * computes it: 0/0 when d is 0. */
static mt_real odd_fraction_pbrt(mt_real c, mt_real d)
{
    return (bumpint(c + d) - bumpint(c - d)) / (2 * d);
}

/* The same average, exact when the interval lies inside one check (its
 * check's parity, which is also the point sample when d is 0): pbrt-v2's
 * formula there is 0/0 (d = 0) or cancellation (c +- d rounds to c). */
static mt_real odd_fraction_exact(mt_real c, mt_real d)
{
    if (mt_floor(c - d) == mt_floor(c + d)) return mt__floor_odd(c) ? 1 : 0;
    return odd_fraction_pbrt(c, d);
}

/* The weight of tex2: 0 or 1 for a point sample, the filtered fraction
 * otherwise (pbrt-v2 Checkerboard2DTexture::Evaluate). */
static mt_real weight2d(const checker *c, const mt_diffgeom *dg)
{
    mt_st st;
    mt_real ds, dt, sint, tint, area2;
    mt__map2d_apply(&c->map2, dg, &st);
    if (c->closedform) {
        ds = mt_max(mt_fabs(st.dsdx), mt_fabs(st.dsdy));
        dt = mt_max(mt_fabs(st.dtdx), mt_fabs(st.dtdy));
        if (mt_floor(st.s - ds) != mt_floor(st.s + ds) ||
            mt_floor(st.t - dt) != mt_floor(st.t + dt)) {
            if (c->pair.base.mode & MT_FIX_CHECKER_ONE_SIDED) {
                sint = odd_fraction_exact(st.s, ds);
                tint = odd_fraction_exact(st.t, dt);
            } else {
                /* pbrt-v2's formula; where it is 0/0 (a zero width) the
                 * zero-width axis is point-sampled: the limit of the formula
                 * as that width tends to 0 (erratum checker-one-sided) */
                sint = ds == 0 ? (mt_real)mt__floor_odd(st.s) : odd_fraction_pbrt(st.s, ds);
                tint = dt == 0 ? (mt_real)mt__floor_odd(st.t) : odd_fraction_pbrt(st.t, dt);
            }
            /* the probability that exactly one of the two parities is odd */
            area2 = sint + tint - 2 * sint * tint;
            if (ds > 1 || dt > 1) area2 = (mt_real)0.5;
            return area2;
        }
    }
    return mt__floor_odd(st.s) != mt__floor_odd(st.t) ? 1 : 0;
}

static mt_real weight3d(const checker *c, const mt_diffgeom *dg)
{
    mt_vec3 dpdx, dpdy, p = mt__map3d_apply(&c->map3, dg, &dpdx, &dpdy);
    return (mt__floor_odd(p.x) ^ mt__floor_odd(p.y) ^ mt__floor_odd(p.z)) ? 1 : 0;
}

static mt_real weight(const mt_texture *t, const mt_diffgeom *dg)
{
    const checker *c = (const checker *)t;
    return c->dim == 2 ? weight2d(c, dg) : weight3d(c, dg);
}

static const mt_texture_ops checker_ops = {
    .name = "checkerboard",
    .eval_float = mt__pair_pick_float,
    .eval_rgb = mt__pair_pick_rgb,
    .finalize = mt__pair_finalize,
};

static checker *checker_alloc(int is_float, mt_texture *tex1, mt_texture *tex2, mt_mode mode,
                              mt_error *err)
{
    checker *c = mt__pair_alloc(sizeof(checker), &checker_ops, is_float, tex1, "tex1", tex2,
                                "tex2", mode, err);
    if (c) c->pair.weight = weight;
    return c;
}

mt_texture *mt__tex_checker2d(int is_float, const mt_map2d *map, mt_texture *tex1,
                              mt_texture *tex2, int closedform, mt_mode mode, mt_error *err)
{
    checker *c;
    if (mt__map2d_check(map, "checkerboard", err)) return NULL;
    c = checker_alloc(is_float, tex1, tex2, mode, err);
    if (!c) return NULL;
    c->dim = 2;
    c->closedform = closedform ? 1 : 0;
    c->map2 = *map;
    return &c->pair.base;
}

mt_texture *mt__tex_checker3d(int is_float, const mt_map3d *map, mt_texture *tex1,
                              mt_texture *tex2, mt_mode mode, mt_error *err)
{
    checker *c = checker_alloc(is_float, tex1, tex2, mode, err);
    if (!c) return NULL;
    c->dim = 3;
    c->map3 = *map;
    return &c->pair.base;
}

static mt_texture *checkerboard_create(int is_float, const mt_transform *tex2world, const mt_texparams *tp,
                          mt_error *err)
{
    static const char *const aamodes[] = {"none", "closedform", NULL};
    mt__tex_children c;
    mt_texture *t = NULL;
    mt_map2d m2;
    mt_map3d m3;
    int dim, aa;
    if (mt_texparams_int(tp, "dimension", 2, &dim, err)) return NULL;
    if (dim != 2 && dim != 3) {
        mt_error_param(err, MT_ERR_INVALID, "dimension",
                       "checkerboard texture: %d dimensions (2 or 3 are supported)", dim);
        return NULL;
    }
    if (!mt__tex_children_get(tp, is_float, "tex1", 1, "tex2", 0, &c, err)) {
        mt__tex_children_put(&c);
        return NULL;
    }
    if (dim == 3) {
        m3 = mt__map3d(tex2world, tp->mode);
        t = mt__tex_checker3d(is_float, &m3, c.a, c.b, tp->mode, err);
    } else if (!mt__tex_mapping2d(tex2world, tp, "checkerboard", &m2, err) &&
               (aa = mt__tex_choice(tp, "aamode", "closedform", aamodes, "checkerboard", err)) >= 0) {
        t = mt__tex_checker2d(is_float, &m2, c.a, c.b, aa, tp->mode, err);
    }
    mt__tex_children_put(&c);
    return t;
}

static const mt__texture_param_doc checkerboard_params[] = {
    {"dimension", "2 or 3", "2: on (u, v); 3: in space (no mapping, no antialiasing)"},
    {"tex1", "any", "the even squares"},
    {"tex2", "any", "the odd squares"},
    {"aamode", "none or closedform", "2D antialiasing: none, or the closed-form box filter"},
};

const mt_texture_kind mt_checkerboard_texture = {
    .name = "checkerboard",
    .has_float = 1,
    .create = checkerboard_create,
    .params = checkerboard_params,
    .nparams = MT_COUNT(checkerboard_params),
};
