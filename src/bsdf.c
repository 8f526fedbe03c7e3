/*
 * The BSDF (pbrt-v2 reflection.h/.cpp BSDF): a shading frame, the geometric
 * normal, and up to MT_MAX_BXDFS components. This is where the light-leak
 * rule lives: whether a pair of directions is reflection or transmission is
 * decided by the geometric normal, not by the shading frame.
 */
#include "materia/bsdf.h"
#include "materia/sampling.h"
#include "core/dir.h"
#include "bsdf_internal.h"

struct mt_bsdf {
    mt_diffgeom dgs;
    mt_vec3 ng;
    mt_frame frame; /* s = sn, t = tn, n = nn */
    mt_real eta;
    mt_mode mode;
    int n;
    mt_bxdf *bxdfs[MT_MAX_BXDFS];
};

static int usable(mt_vec3 v) { return mt_v3_is_finite(v) && !mt_v3_is_zero(v); }

mt_bsdf *mt_bsdf_create(mt_arena *a, mt_mode mode, const mt_diffgeom *dgs, mt_vec3 ng,
                        mt_real eta, mt_error *err)
{
    mt_error_clear(err);
    return mt__bsdf_create(a, mode, dgs, ng, eta, err);
}

mt_bsdf *mt__bsdf_create(mt_arena *a, mt_mode mode, const mt_diffgeom *dgs, mt_vec3 ng,
                         mt_real eta, mt_error *err)
{
    mt_bsdf *b;
    mt_vec3 nn = dgs->n, sn = dgs->dpdu;
    if (!usable(nn) || !usable(ng) || !mt_is_finite(eta)) {
        mt_error_set(err, MT_ERR_INVALID,
                     "bsdf: the shading normal, geometric normal and eta must be finite and "
                     "the normals non-zero");
        return NULL;
    }
    b = mt_arena_alloc(a, sizeof *b);
    if (!b) {
        mt_error_set(err, MT_ERR_NOMEM, "out of memory allocating a BSDF");
        return NULL;
    }
    mt__admit_dir(&nn);
    if (mode & MT_FIX_BSDF_FRAME) /* erratum bsdf-frame: make dpdu perpendicular */
        sn = mt_v3_sub(sn, mt_v3_scale(nn, mt_v3_dot(nn, sn)));
    if (usable(sn) && mt_is_finite(mt_v3_len2(sn)) && mt_v3_len2(sn) > 0) {
        sn = mt_v3_normalize(sn);
        b->frame.s = sn;
        b->frame.t = mt_v3_cross(nn, sn);
        b->frame.n = nn;
    } else {
        /* dpdu = 0 (a sphere's pole): pbrt-v2 normalizes the zero vector (NaN);
         * any tangent will do for the isotropic frame (erratum zero-dpdu). */
        b->frame = mt_frame_from_normal(nn);
    }
    b->dgs = *dgs;
    b->ng = ng;
    b->eta = eta;
    b->mode = mode;
    b->n = 0;
    return b;
}

mt_status mt_bsdf_add(mt_bsdf *b, mt_bxdf *bxdf, mt_error *err)
{
    if (b && bxdf) mt_error_clear(err);
    return mt__bsdf_add(b, bxdf, err);
}

mt_status mt__bsdf_add(mt_bsdf *b, mt_bxdf *bxdf, mt_error *err)
{
    if (!b || !bxdf) {
        /* A creator failed and filled err (or had no err to fill): its error
         * is the one to report, so err is not reset here. */
        if (err && err->status != MT_OK) return err->status;
        return mt_error_set(err, MT_ERR_INVALID, b ? "bsdf: no BxDF to add" : "bsdf: no BSDF to add to");
    }
    if (b->n >= MT_MAX_BXDFS)
        return mt_error_set(err, MT_ERR_LIMIT, "bsdf: more than %d BxDFs (adding a %s)",
                            MT_MAX_BXDFS, bxdf->ops->name);
    b->bxdfs[b->n++] = bxdf;
    return MT_OK;
}

int mt_bsdf_num_components(const mt_bsdf *b, unsigned flags)
{
    int i, num = 0;
    for (i = 0; i < b->n; ++i)
        if (mt_type_matches(b->bxdfs[i]->type, flags)) ++num;
    return num;
}

int mt_bsdf_count(const mt_bsdf *b) { return b->n; }
mt_bxdf *mt_bsdf_component(const mt_bsdf *b, int i) { return i >= 0 && i < b->n ? b->bxdfs[i] : NULL; }
mt_real mt_bsdf_eta(const mt_bsdf *b) { return b->eta; }
mt_mode mt_bsdf_mode(const mt_bsdf *b) { return b->mode; }
const mt_diffgeom *mt_bsdf_shading(const mt_bsdf *b) { return &b->dgs; }
mt_vec3 mt_bsdf_ng(const mt_bsdf *b) { return b->ng; }
mt_frame mt_bsdf_frame(const mt_bsdf *b) { return b->frame; }
mt_vec3 mt_bsdf_world_to_local(const mt_bsdf *b, mt_vec3 v) { return mt_frame_to_local(&b->frame, v); }
mt_vec3 mt_bsdf_local_to_world(const mt_bsdf *b, mt_vec3 v) { return mt_frame_to_world(&b->frame, v); }

/* The light-leak rule: the flags f may use for the world pair (wo, wi).
 * Returns 0 when the pair carries no energy (corrected mode, a direction in
 * the geometric tangent plane). */
static unsigned leak_flags(const mt_bsdf *b, mt_vec3 wo, mt_vec3 wi, unsigned flags)
{
    mt_real di = mt_v3_dot(wi, b->ng), d_o = mt_v3_dot(wo, b->ng);
    if (b->mode & MT_FIX_TANGENT_PLANE) {
        /* Signs rather than the product, which underflows to 0 for tiny
         * cosines and would count them as transmission too. */
        if (di == 0 || d_o == 0) return 0;
        return (di > 0) == (d_o > 0) ? flags & ~(unsigned)MT_BSDF_TRANSMISSION
                                      : flags & ~(unsigned)MT_BSDF_REFLECTION;
    }
    /* pbrt-v2: reflection iff Dot(wi, ng) * Dot(wo, ng) > 0 (erratum tangent-plane) */
    return di * d_o > 0 ? flags & ~(unsigned)MT_BSDF_TRANSMISSION
                        : flags & ~(unsigned)MT_BSDF_REFLECTION;
}

/* The sum of f over the components that match flags. `known`, when not NULL,
 * is a component whose f(wo, wi) is already known to be known_f. */
static mt_rgb sum_f(const mt_bsdf *b, mt_vec3 wo, mt_vec3 wi, unsigned flags, const mt_bxdf *known,
                    mt_rgb known_f)
{
    mt_rgb f = mt_rgb_black();
    int i;
    for (i = 0; i < b->n; ++i)
        if (mt_type_matches(b->bxdfs[i]->type, flags))
            f = mt_rgb_add(f, b->bxdfs[i] == known ? known_f : b->bxdfs[i]->ops->f(b->bxdfs[i], wo, wi));
    return f;
}

mt_rgb mt_bsdf_f(const mt_bsdf *b, mt_vec3 woW, mt_vec3 wiW, unsigned flags)
{
    if (!mt__admit_dir(&woW) || !mt__admit_dir(&wiW)) return mt_rgb_black();
    flags = leak_flags(b, woW, wiW, flags);
    if (!flags) return mt_rgb_black();
    return sum_f(b, mt_frame_to_local(&b->frame, woW), mt_frame_to_local(&b->frame, wiW), flags, NULL,
                 mt_rgb_black());
}

/* The pdf's sum over the components that match flags, local directions. */
static mt_real sum_pdf(const mt_bsdf *b, mt_vec3 wo, mt_vec3 wi, unsigned flags)
{
    mt_real pdf = 0;
    int i, matching = 0;
    for (i = 0; i < b->n; ++i)
        if (mt_type_matches(b->bxdfs[i]->type, flags)) {
            ++matching;
            pdf += b->bxdfs[i]->ops->pdf(b->bxdfs[i], wo, wi);
        }
    return matching > 0 ? pdf / matching : 0;
}

mt_rgb mt__bsdf_f_pair(const mt_bsdf *b, const mt__bsdf_wo *o, mt_vec3 wiW, unsigned flags, mt__bsdf_pair *pair)
{
    unsigned fl;
    pair->ok = o->ok && mt__admit_dir(&wiW);
    if (!pair->ok) return mt_rgb_black();
    pair->wo = o->local;
    pair->wi = mt_frame_to_local(&b->frame, wiW);
    fl = leak_flags(b, o->w, wiW, flags);
    if (!fl) return mt_rgb_black();
    return sum_f(b, pair->wo, pair->wi, fl, NULL, mt_rgb_black());
}

mt_real mt__bsdf_pdf_pair(const mt_bsdf *b, const mt__bsdf_pair *pair, unsigned flags)
{
    if (b->n == 0 || !pair->ok) return 0;
    return sum_pdf(b, pair->wo, pair->wi, flags);
}

static mt_bsdf_sample failed_sample(void)
{
    mt_bsdf_sample s;
    s.wi = mt_v3(0, 0, 0);
    s.f = mt_rgb_black();
    s.pdf = 0;
    s.type = 0;
    return s;
}

void mt__bsdf_wo_init(const mt_bsdf *b, mt_vec3 woW, mt__bsdf_wo *o)
{
    o->w = woW;
    o->ok = mt__admit_dir(&o->w);
    if (o->ok) o->local = mt_frame_to_local(&b->frame, o->w);
}

mt_bsdf_sample mt_bsdf_sample_f(const mt_bsdf *b, mt_vec3 woW, mt_real uc, mt_real u1,
                                mt_real u2, unsigned flags)
{
    mt__bsdf_wo o;
    mt__bsdf_wo_init(b, woW, &o);
    return mt__bsdf_sample_f_wo(b, &o, uc, u1, u2, flags);
}

mt_bsdf_sample mt__bsdf_sample_f_wo(const mt_bsdf *b, const mt__bsdf_wo *o, mt_real uc, mt_real u1,
                                    mt_real u2, unsigned flags)
{
    mt_bsdf_sample s = failed_sample();
    int matching, which, i;
    const mt_bxdf *bxdf, *match[MT_MAX_BXDFS];
    mt_vec3 wo, wi, woW = o->w;
    if (!o->ok || !(uc >= 0 && uc < 1) || !(u1 >= 0 && u1 < 1) || !(u2 >= 0 && u2 < 1))
        return s;
    /* pbrt-v2: which = min(Floor2Int(u * matching), matching - 1), then the
     * which-th matching component; u >= 0, so truncation is the floor */
    for (i = matching = 0; i < b->n; ++i)
        if (mt_type_matches(b->bxdfs[i]->type, flags)) match[matching++] = b->bxdfs[i];
    if (matching == 0) return s;
    which = (int)(uc * matching);
    if (which > matching - 1) which = matching - 1;
    bxdf = match[which];
    wo = o->local;
    s.pdf = 0;
    s.f = bxdf->ops->sample_f(bxdf, wo, &wi, u1, u2, &s.pdf);
    if (s.pdf == 0) return failed_sample();
    s.type = bxdf->type;
    s.wi = mt_frame_to_world(&b->frame, wi);
    if (!(bxdf->type & MT_BSDF_SPECULAR) && matching > 1)
        for (i = 0; i < matching; ++i)
            if (match[i] != bxdf) s.pdf += match[i]->ops->pdf(match[i], wo, wi);
    if (matching > 1) s.pdf /= matching;
    if (!(bxdf->type & MT_BSDF_SPECULAR)) {
        /* f summed over the components the light-leak rule admits. The
         * sampled component's Sample_f already returned its f(wo, wi) (the
         * BxDF contract) when wi lies on its own side; otherwise (pbrt-v2's
         * glossy samples below the horizon return 0) it is evaluated again,
         * as pbrt-v2 does. */
        unsigned fl = leak_flags(b, woW, s.wi, flags);
        int own_side = mt_same_hemisphere(wo, wi) == !(bxdf->type & MT_BSDF_TRANSMISSION);
        s.f = fl ? sum_f(b, wo, wi, fl, own_side ? bxdf : NULL, s.f) : mt_rgb_black();
    }
    return s;
}

mt_real mt_bsdf_pdf(const mt_bsdf *b, mt_vec3 woW, mt_vec3 wiW, unsigned flags)
{
    if (b->n == 0 || !mt__admit_dir(&woW) || !mt__admit_dir(&wiW)) return 0;
    return sum_pdf(b, mt_frame_to_local(&b->frame, woW), mt_frame_to_local(&b->frame, wiW), flags);
}

/* Rows of the stratified grid are generated and consumed one at a time, so no
 * allocation is needed whatever sqrt_samples is: every estimator here is a
 * mean over samples, and the mean of equal-sized row means is the same. */
#define MAX_ROW 1024

static int clamp_strata(int sqrt_samples)
{
    return sqrt_samples < 1 ? 1 : (sqrt_samples > MAX_ROW ? MAX_ROW : sqrt_samples);
}

mt_rgb mt_bsdf_rho_hd(const mt_bsdf *b, mt_vec3 woW, mt_rng *rng, unsigned flags,
                      int sqrt_samples)
{
    mt_real row[2 * MAX_ROW];
    mt_rgb ret = mt_rgb_black();
    mt_vec3 wo;
    int n = clamp_strata(sqrt_samples), y, i;
    if (!mt__admit_dir(&woW)) return ret;
    /* pbrt-v2 hands the world-space wo to BxDF::rho (erratum rho-world-space). */
    wo = (b->mode & MT_FIX_RHO_LOCAL) ? mt_frame_to_local(&b->frame, woW) : woW;
    for (y = 0; y < n; ++y) {
        mt_stratified_row_2d(row, n, n, y, rng, 1);
        for (i = 0; i < b->n; ++i)
            if (mt_type_matches(b->bxdfs[i]->type, flags))
                ret = mt_rgb_add(ret, b->bxdfs[i]->ops->rho_hd(b->bxdfs[i], wo, n, row));
    }
    return mt_rgb_scale(ret, (mt_real)1 / n);
}

mt_rgb mt_bsdf_rho_hh(const mt_bsdf *b, mt_rng *rng, unsigned flags, int sqrt_samples)
{
    mt_real r1[2 * MAX_ROW], r2[2 * MAX_ROW];
    mt_rgb ret = mt_rgb_black();
    int n = clamp_strata(sqrt_samples), y, i;
    for (y = 0; y < n; ++y) {
        mt_stratified_row_2d(r1, n, n, y, rng, 1);
        mt_stratified_row_2d(r2, n, n, y, rng, 1);
        for (i = 0; i < b->n; ++i)
            if (mt_type_matches(b->bxdfs[i]->type, flags))
                ret = mt_rgb_add(ret, b->bxdfs[i]->ops->rho_hh(b->bxdfs[i], n, r1, r2));
    }
    return mt_rgb_scale(ret, (mt_real)1 / n);
}

/* The mix material replaces components with scaled ones (pbrt-v2's
 * MixMaterial is the BSDF's friend for exactly this). */
void mt__bsdf_set_component(mt_bsdf *b, int i, mt_bxdf *x)
{
    if (i >= 0 && i < b->n && x) b->bxdfs[i] = x;
}
