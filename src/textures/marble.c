/*
 * pbrt-v2 MarbleTexture (textures/marble.h): t = 1/2 + sin(y + variation
 * FBm)/2 of the scaled 3D-mapped point, through a cubic Bezier spline over a
 * table of 9 colours (6 segments), times 1.5. Spectrum only, as in pbrt-v2.
 *
 * At t = 1 pbrt-v2 takes segment first = 6 and reads c[first + 3] = c[9],
 * one past the table (erratum marble-index). That entry's weight is then
 * exactly 0 (t - first = 0), so whatever finite value the compiled program
 * finds there, pbrt-v2's answer is 1.5 c[6]; in pbrt-v2 mode materia uses
 * c[8] in its place (same answer, no out-of-bounds read). Corrected mode
 * clamps first to 5 as pbrt-v4 does: the end of the last segment, 1.5 c[8].
 * With pbrt-v2's table c[6] = c[8], so the two modes agree at t = 1.
 */
#include "textures/noise.h"
#include "textures/create.h"

#define NC 9
#define NSEG (NC - 3)

typedef struct marble {
    mt__noise_tex noise;
    mt_real scale, variation;
} marble;

static const float colors[NC][3] = {
    {.58f, .58f, .6f}, {.58f, .58f, .6f}, {.58f, .58f, .6f}, {.5f, .5f, .5f},  {.6f, .59f, .58f},
    {.58f, .58f, .6f}, {.58f, .58f, .6f}, {.2f, .2f, .33f},  {.58f, .58f, .6f}};

static mt_real marble_float(const mt_texture *t, const mt_diffgeom *dg)
{
    (void)t;
    (void)dg;
    return 0; /* never called: the constructor makes spectrum variants only */
}

/* de Casteljau's evaluation of one component of the segment starting at
 * colors[first] (c3 is colors[i3]). */
static mt_real bezier(int first, int i3, mt_real t, int k)
{
    mt_real c0 = colors[first][k], c1 = colors[first + 1][k], c2 = colors[first + 2][k];
    mt_real c3 = colors[i3][k];
    mt_real s0 = (1 - t) * c0 + t * c1, s1 = (1 - t) * c1 + t * c2, s2 = (1 - t) * c2 + t * c3;
    s0 = (1 - t) * s0 + t * s1;
    s1 = (1 - t) * s1 + t * s2;
    return (mt_real)1.5 * ((1 - t) * s0 + t * s1);
}

static mt_rgb marble_rgb(const mt_texture *tex, const mt_diffgeom *dg)
{
    const marble *m = (const marble *)tex;
    mt_vec3 dpdx, dpdy, p = mt__map3d_apply(&m->noise.map, dg, &dpdx, &dpdy);
    mt_real value, t, ft;
    int first, i3;
    p = mt_v3_scale(p, m->scale);
    value = p.y + m->variation * mt__fbm(p, mt_v3_scale(dpdx, m->scale),
                                         mt_v3_scale(dpdy, m->scale), m->noise.omega,
                                         m->noise.octaves);
    /* only a point so far out that scale * p overflowed gets here non-finite */
    if (!mt_is_finite(value)) value = 0;
    t = (mt_real)0.5 + (mt_real)0.5 * mt_sin(value);
    ft = t * NSEG;
    /* t is in [0, 1], so first is in [0, NSEG]; the clamp only keeps the
     * reads in bounds whatever the math library's sin returns */
    first = (int)mt_clamp(mt_floor(ft), 0, NSEG);
    if ((tex->mode & MT_FIX_MARBLE_INDEX) && first > NSEG - 1) first = NSEG - 1;
    i3 = first + 3 < NC ? first + 3 : NC - 1;
    t = ft - (mt_real)first;
    return mt_rgb_make(bezier(first, i3, t, 0), bezier(first, i3, t, 1), bezier(first, i3, t, 2));
}

static const mt_texture_ops marble_ops = {
    .name = "marble",
    .eval_float = marble_float,
    .eval_rgb = marble_rgb,
};

mt_texture *mt__tex_marble(const mt_map3d *map, int octaves, mt_real roughness, mt_real scale,
                           mt_real variation, mt_mode mode, mt_error *err)
{
    marble *m;
    if (!mt__tex_check_real(scale, "scale", "marble", err) ||
        !mt__tex_check_real(variation, "variation", "marble", err))
        return NULL;
    m = mt__noise_alloc(sizeof *m, &marble_ops, 0, map, octaves, roughness, mt__fbm, mode, err);
    if (!m) return NULL;
    m->scale = scale;
    m->variation = variation;
    return &m->noise.base;
}

static mt_texture *marble_create(int is_float, const mt_transform *tex2world, const mt_texparams *tp,
                          mt_error *err)
{
    mt_map3d m = mt__map3d(tex2world, tp->mode);
    mt_real rough, scale, variation;
    int oct;
    if (mt__tex_octaves(tp, &oct, &rough, err) || mt_texparams_float(tp, "scale", 1, &scale, err) ||
        mt_texparams_float(tp, "variation", (mt_real)0.2, &variation, err))
        return NULL;
    return mt__tex_marble(&m, oct, rough, scale, variation, tp->mode, err);
}

static const mt__texture_param_doc marble_params[] = {
    {"scale", "finite", "the point's coordinates times scale"},
    {"variation", "finite", "the strength of the noise in the marble's bands"},
};

const mt_texture_kind mt_marble_texture = {
    .name = "marble",
    .has_float = 0,
    .create = marble_create,
    .params = marble_params,
    .nparams = MT_COUNT(marble_params),
};
