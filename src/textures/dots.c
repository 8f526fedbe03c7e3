/*
 * pbrt-v2 DotsTexture (textures/dots.h): a dot of radius 0.35 in some cells
 * of the (s, t) lattice (those where Noise at the cell centre is positive),
 * shifted by up to 0.15 by noise.
 *
 * pbrt-v2's constructor takes (outsideDot, insideDot) and its creators pass
 * the "inside" parameter first, so "inside" is drawn around the dots and
 * "outside" on them (erratum dots-inside, visible in the reference values);
 * MT_FIX_DOTS_INSIDE puts "inside" on the dots.
 */
#include "textures/noise.h"
#include "textures/create.h"

typedef struct dots {
    mt__pair_tex pair; /* tex1 around the dots, tex2 on them */
    mt_map2d map;
} dots;

/* 1 on a dot, 0 around the dots. */
static mt_real on_dot(const mt_texture *t, const mt_diffgeom *dg)
{
    mt_st st;
    mt_real scell, tcell;
    mt__map2d_apply(&((const dots *)t)->map, dg, &st);
    /* Floor2Int(s + .5f), kept as a real: the same value without overflow */
    scell = mt_floor(st.s + (mt_real)0.5);
    tcell = mt_floor(st.t + (mt_real)0.5);
    if (mt__noise(scell + (mt_real)0.5, tcell + (mt_real)0.5, (mt_real)0.5) > 0) {
        mt_real radius = (mt_real)0.35;
        mt_real max_shift = (mt_real)0.5 - radius;
        mt_real sc = scell + max_shift * mt__noise(scell + (mt_real)1.5, tcell + (mt_real)2.8,
                                                   (mt_real)0.5);
        mt_real tc = tcell + max_shift * mt__noise(scell + (mt_real)4.5, tcell + (mt_real)9.8,
                                                   (mt_real)0.5);
        mt_real ds = st.s - sc, dt = st.t - tc;
        if (ds * ds + dt * dt < radius * radius) return 1;
    }
    return 0;
}

static const mt_texture_ops dots_ops = {
    .name = "dots",
    .eval_float = mt__pair_pick_float,
    .eval_rgb = mt__pair_pick_rgb,
    .finalize = mt__pair_finalize,
};

mt_texture *mt__tex_dots(int is_float, const mt_map2d *map, mt_texture *inside_tex,
                         mt_texture *outside_tex, mt_mode mode, mt_error *err)
{
    dots *d;
    if (mt__map2d_check(map, "dots", err)) return NULL;
    if (mode & MT_FIX_DOTS_INSIDE)
        d = mt__pair_alloc(sizeof *d, &dots_ops, is_float, outside_tex, "outside", inside_tex,
                           "inside", mode, err);
    else
        d = mt__pair_alloc(sizeof *d, &dots_ops, is_float, inside_tex, "inside", outside_tex,
                           "outside", mode, err);
    if (!d) return NULL;
    d->pair.weight = on_dot;
    d->map = *map;
    return &d->pair.base;
}

static mt_texture *dots_create(int is_float, const mt_transform *tex2world, const mt_texparams *tp,
                          mt_error *err)
{
    mt__tex_children c;
    mt_map2d m;
    mt_texture *t = NULL;
    if (mt__tex_mapping2d(tex2world, tp, "dots", &m, err)) return NULL;
    if (mt__tex_children_get(tp, is_float, "inside", 1, "outside", 0, &c, err))
        t = mt__tex_dots(is_float, &m, c.a, c.b, tp->mode, err);
    mt__tex_children_put(&c);
    return t;
}

static const mt__texture_param_doc dots_params[] = {
    {"inside", "any", "inside the dots"},
    {"outside", "any", "between the dots"},
};

const mt_texture_kind mt_dots_texture = {
    .name = "dots",
    .has_float = 1,
    .create = dots_create,
    .params = dots_params,
    .nparams = MT_COUNT(dots_params),
};
