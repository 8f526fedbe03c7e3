/*
 * impl-other [BUG]: a material system that is not pbrt-v2's, behind the
 * query protocol, for proving that materia-conformance judges another
 * renderer by physics alone (tests/test_impl.c). Its materials carry
 * pbrt-v2's names and parameters, but they are pbrt-v3's models, computed in
 * float as a GPU renderer would:
 *
 *   matte       Lambertian, or Oren-Nayar when sigma > 0
 *   plastic     Lambertian + Trowbridge-Reitz reflection, Fresnel of a
 *               dielectric of index 1.5
 *   metal       Trowbridge-Reitz reflection, conductor Fresnel (copper by
 *               default, eta and k as rgb)
 *   mirror      specular reflection
 *   glass       one Fresnel-weighted specular lobe (pbrt-v3's FresnelSpecular):
 *               reflection with probability F, else transmission
 *   substrate   FresnelBlend with a Trowbridge-Reitz distribution
 *   roughglass  (its own) Trowbridge-Reitz reflection and transmission
 *
 * A roughness r of pbrt-v2 (the Blinn exponent 1/r) becomes the
 * Trowbridge-Reitz alpha of the same width, sqrt(2 / (1/r + 2)); microfacet
 * normals are sampled where they are visible (Heitz 2018). Its conventions
 * are pbrt-v3's: transport radiance (a transmission scaled by
 * (eta_o/eta_i)^2) and two random numbers (uc chooses the component and is
 * rescaled to drive it, u1 the second, u2 unused). Textures, named
 * materials, transforms and the other materials are answered "error
 * unsupported: ...".
 *
 * BUG plants one real bug a renderer had, each the kind the suite must
 * catch with physics alone:
 *   nearnormal      pbrt-v3's microfacet sampler (Heitz 2014, stretched
 *                   slopes rotated by the azimuth of the stretched wo, whose
 *                   sin theta is sqrt(1 - cos^2)): near the normal with a
 *                   low roughness 1 - cos^2 cancels in float, sin theta is
 *                   off by tens of percent, and the rotation (cos phi,
 *                   sin phi), clamped to [-1, 1], scales the slopes by that
 *                   factor except at phi 0 or 90 degrees, where the clamp
 *                   makes it exact: the sampled lobe is wider than its pdf
 *   facing          the rough dielectric's transmission f and pdf positive
 *                   where the microfacet faces away from wo (pbrt-v3's
 *                   MicrofacetTransmission tests only that wo and wi are on
 *                   opposite sides of it), where its sampler never goes
 *   blend-negative  FresnelBlend's pdf: its glossy half's density of visible
 *                   normals divided by cos theta_o, guarded at grazing by
 *                   "if (c < 2e-4) c -= 2e-4" where "c = 2e-4" was meant: for
 *                   cos theta_o below 2e-4 the pdf is negative
 *   none            no bug
 */
#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "support/answer_out.h"

#define PI_F 3.14159265358979f
#define ONE_MINUS_EPS 0x1.fffffep-1f

static const char *bug = "none";
static int is_bug(const char *b) { return !strcmp(bug, b); }

/* ---- vectors in float ------------------------------------------------------ */
typedef struct v3 {
    float x, y, z;
} v3;

static v3 mk(float x, float y, float z)
{
    v3 v;
    v.x = x;
    v.y = y;
    v.z = z;
    return v;
}
static float dot(v3 a, v3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static v3 add(v3 a, v3 b) { return mk(a.x + b.x, a.y + b.y, a.z + b.z); }
static v3 scale(v3 a, float s) { return mk(a.x * s, a.y * s, a.z * s); }
static v3 neg(v3 a) { return mk(-a.x, -a.y, -a.z); }
static v3 cross(v3 a, v3 b) { return mk(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x); }
static float len(v3 a) { return sqrtf(dot(a, a)); }
static v3 norm(v3 a)
{
    float l = len(a);
    return l > 0 ? scale(a, 1 / l) : a;
}

typedef struct rgb {
    float c[3];
} rgb;
static rgb gray(float v)
{
    rgb r;
    r.c[0] = r.c[1] = r.c[2] = v;
    return r;
}

/* ---- the Trowbridge-Reitz distribution (pbrt-v3, microfacet.cpp) -------- */
typedef struct tr {
    float ax, ay;
} tr;

static float cos2(v3 w) { return w.z * w.z; }

static float tr_d(const tr *d, v3 wh)
{
    float t2 = (wh.x * wh.x + wh.y * wh.y) / (wh.z * wh.z), c4, e, s2 = wh.x * wh.x + wh.y * wh.y;
    if (!(wh.z != 0) || isinf(t2)) return 0;
    c4 = cos2(wh) * cos2(wh);
    e = s2 > 0 ? t2 * ((wh.x * wh.x / s2) / (d->ax * d->ax) + (wh.y * wh.y / s2) / (d->ay * d->ay)) : 0;
    return 1 / (PI_F * d->ax * d->ay * c4 * (1 + e) * (1 + e));
}

static float tr_lambda(const tr *d, v3 w)
{
    float s2 = w.x * w.x + w.y * w.y, a2, t2;
    if (!(w.z != 0)) return INFINITY;
    t2 = s2 / (w.z * w.z);
    if (isinf(t2)) return 0;
    a2 = s2 > 0 ? (w.x * w.x / s2) * d->ax * d->ax + (w.y * w.y / s2) * d->ay * d->ay : d->ax * d->ax;
    return (-1 + sqrtf(1 + a2 * t2)) / 2;
}

static float tr_g1(const tr *d, v3 w) { return 1 / (1 + tr_lambda(d, w)); }
static float tr_g(const tr *d, v3 a, v3 b) { return 1 / (1 + tr_lambda(d, a) + tr_lambda(d, b)); }

/* The density of the visible normals seen from wo. */
static float tr_pdf(const tr *d, v3 wo, v3 wh)
{
    return tr_d(d, wh) * tr_g1(d, wo) * fabsf(dot(wo, wh)) / fabsf(wo.z);
}

/* Visible normals, Heitz 2018 ("Sampling the GGX Distribution of Visible
 * Normals"), for wo above; exact in float near the normal. */
static v3 vndf_2018(const tr *d, v3 wo, float u1, float u2)
{
    v3 vh = norm(mk(d->ax * wo.x, d->ay * wo.y, wo.z)), t1, t2, nh;
    float l2 = vh.x * vh.x + vh.y * vh.y, r = sqrtf(u1), phi = 2 * PI_F * u2, p1, p2, s;
    t1 = l2 > 0 ? scale(mk(-vh.y, vh.x, 0), 1 / sqrtf(l2)) : mk(1, 0, 0);
    t2 = cross(vh, t1);
    p1 = r * cosf(phi);
    p2 = r * sinf(phi);
    s = 0.5f * (1 + vh.z);
    p2 = (1 - s) * sqrtf(fmaxf(0, 1 - p1 * p1)) + s * p2;
    nh = add(add(scale(t1, p1), scale(t2, p2)), scale(vh, sqrtf(fmaxf(0, 1 - p1 * p1 - p2 * p2))));
    return norm(mk(d->ax * nh.x, d->ay * nh.y, fmaxf(1e-6f, nh.z)));
}

/* pbrt-v3's TrowbridgeReitzSample11: slopes of the visible normals at
 * incidence cos theta, for alpha 1. */
static void sample11(float cos_t, float u1, float u2, float *sx, float *sy)
{
    float sin_t, tan_t, a, g1, aa, tmp, b, dd, x1, x2, s, z;
    if (cos_t > .9999f) { /* normal incidence */
        float r = sqrtf(u1 / (1 - u1)), phi = 6.28318530718f * u2;
        *sx = r * cosf(phi);
        *sy = r * sinf(phi);
        return;
    }
    sin_t = sqrtf(fmaxf(0, 1 - cos_t * cos_t));
    tan_t = sin_t / cos_t;
    a = 1 / tan_t;
    g1 = 2 / (1 + sqrtf(1 + 1 / (a * a)));
    aa = 2 * u1 / g1 - 1;
    tmp = 1 / (aa * aa - 1);
    if (tmp > 1e10f) tmp = 1e10f;
    b = tan_t;
    dd = sqrtf(fmaxf(b * b * tmp * tmp - (aa * aa - b * b) * tmp, 0));
    x1 = b * tmp - dd;
    x2 = b * tmp + dd;
    *sx = (aa < 0 || x2 > 1 / tan_t) ? x1 : x2;
    if (u2 > 0.5f) {
        s = 1;
        u2 = 2 * (u2 - .5f);
    } else {
        s = -1;
        u2 = 2 * (.5f - u2);
    }
    z = (u2 * (u2 * (u2 * 0.27385f - 0.73369f) + 0.46341f)) / (u2 * (u2 * (u2 * 0.093073f + 0.309420f) - 1) + 0.597999f);
    *sy = s * z * sqrtf(1 + *sx * *sx);
}

/* pbrt-v3's TrowbridgeReitzSample (Heitz 2014: stretch, sample the slopes,
 * rotate, unstretch), with pbrt-v3's SinTheta = sqrt(max(0, 1 - cos^2)) and
 * CosPhi = clamp(x / SinTheta, -1, 1): the bug "nearnormal". */
static v3 vndf_2014(const tr *d, v3 wo, float u1, float u2)
{
    v3 st = norm(mk(d->ax * wo.x, d->ay * wo.y, wo.z));
    float sx, sy, sin_t = sqrtf(fmaxf(0, 1 - st.z * st.z)), cp, sp, t;
    sample11(st.z, u1, u2, &sx, &sy);
    cp = sin_t == 0 ? 1 : fminf(1, fmaxf(-1, st.x / sin_t));
    sp = sin_t == 0 ? 0 : fminf(1, fmaxf(-1, st.y / sin_t));
    t = cp * sx - sp * sy;
    sy = sp * sx + cp * sy;
    sx = t;
    return norm(mk(-sx * d->ax, -sy * d->ay, 1));
}

static v3 tr_sample(const tr *d, v3 wo, float u1, float u2)
{
    int flip = wo.z < 0;
    v3 w = flip ? neg(wo) : wo, wh = is_bug("nearnormal") ? vndf_2014(d, w, u1, u2) : vndf_2018(d, w, u1, u2);
    return flip ? neg(wh) : wh;
}

/* ---- Fresnel ----------------------------------------------------------------- */
/* A dielectric's reflectance at cos theta_i (negative: from inside), the
 * indices ei outside and et inside. */
static float fr_dielectric(float ci, float ei, float et)
{
    float si, st, ct, rpar, rperp;
    ci = fminf(1, fmaxf(-1, ci));
    if (ci < 0) {
        float t = ei;
        ei = et;
        et = t;
        ci = -ci;
    }
    si = sqrtf(fmaxf(0, 1 - ci * ci));
    st = ei / et * si;
    if (st >= 1) return 1;
    ct = sqrtf(fmaxf(0, 1 - st * st));
    rpar = (et * ci - ei * ct) / (et * ci + ei * ct);
    rperp = (ei * ci - et * ct) / (ei * ci + et * ct);
    return (rpar * rpar + rperp * rperp) / 2;
}

/* A conductor's reflectance (pbrt-v3's FrConductor) at |cos theta_i|. */
static float fr_conductor(float ci, float eta, float k)
{
    float c2 = ci * ci, s2 = 1 - c2, e2 = eta * eta, k2 = k * k, t0 = e2 - k2 - s2;
    float a2b2 = sqrtf(fmaxf(0, t0 * t0 + 4 * e2 * k2)), t1 = a2b2 + c2, a = sqrtf(fmaxf(0, 0.5f * (a2b2 + t0)));
    float t2 = 2 * ci * a, rs = (t1 - t2) / (t1 + t2), t3 = c2 * a2b2 + s2 * s2, t4 = t2 * s2;
    float rp = rs * (t3 - t4) / (t3 + t4);
    return 0.5f * (rp + rs);
}

/* ---- components --------------------------------------------------------------- */
enum { REFL = 1, TRANS = 2, DIFFUSE = 4, GLOSSY = 8, SPECULAR = 16 };
enum { LAMBERT, OREN, MF_REFL, MF_TRANS, SPEC_REFL, FRESNEL_SPEC, BLEND };
enum { FR_NONE, FR_DIEL, FR_COND };

typedef struct comp {
    int kind, fresnel;
    rgb r;          /* its colour (Kd, Ks, Kr, R), or Rd for the blend */
    rgb rs, t;      /* the blend's Rs; glass's Kt */
    rgb eta, k;     /* a conductor's */
    float ior;      /* a dielectric's index inside (outside 1) */
    float A, B;     /* Oren-Nayar */
    tr d;
} comp;

static unsigned comp_flags(const comp *c)
{
    switch (c->kind) {
    case LAMBERT:
    case OREN: return REFL | DIFFUSE;
    case MF_REFL: return REFL | GLOSSY;
    case MF_TRANS: return TRANS | GLOSSY;
    case SPEC_REFL: return REFL | SPECULAR;
    case FRESNEL_SPEC: return REFL | TRANS | SPECULAR;
    default: return REFL | GLOSSY;
    }
}

static int same_side(v3 a, v3 b) { return a.z * b.z > 0; }

static float fresnel_of(const comp *c, float ci, int ch)
{
    if (c->fresnel == FR_DIEL) return fr_dielectric(ci, 1, c->ior);
    if (c->fresnel == FR_COND) return fr_conductor(fabsf(ci), c->eta.c[ch], c->k.c[ch]);
    return 1;
}

/* the generalized half vector of a transmission pair, on wo's side; eta the
 * index ratio inside / outside as seen from wo */
static float trans_eta(const comp *c, v3 wo) { return wo.z > 0 ? c->ior : 1 / c->ior; }

static rgb comp_f(const comp *c, v3 wo, v3 wi)
{
    rgb f = gray(0);
    int k;
    float co = fabsf(wo.z), cii = fabsf(wi.z);
    if (c->kind == LAMBERT || c->kind == OREN) {
        float s = 1 / PI_F;
        if (!same_side(wo, wi)) return f;
        if (c->kind == OREN) {
            float so = sqrtf(fmaxf(0, 1 - wo.z * wo.z)), si = sqrtf(fmaxf(0, 1 - wi.z * wi.z)), mc = 0, sa, tb;
            if (si > 1e-4f && so > 1e-4f) mc = fmaxf(0, (wi.x * wo.x + wi.y * wo.y) / (si * so));
            if (cii > co) {
                sa = so;
                tb = si / cii;
            } else {
                sa = si;
                tb = so / co;
            }
            s *= c->A + c->B * mc * sa * tb;
        }
        for (k = 0; k < 3; ++k) f.c[k] = c->r.c[k] * s;
        return f;
    }
    if (c->kind == MF_REFL) {
        v3 wh;
        if (!same_side(wo, wi) || co == 0 || cii == 0) return f;
        wh = add(wo, wi);
        if (wh.x == 0 && wh.y == 0 && wh.z == 0) return f;
        wh = norm(wh);
        for (k = 0; k < 3; ++k)
            f.c[k] = c->r.c[k] * tr_d(&c->d, wh) * tr_g(&c->d, wo, wi) *
                     fresnel_of(c, dot(wi, wh.z < 0 ? neg(wh) : wh), k) / (4 * co * cii);
        return f;
    }
    if (c->kind == MF_TRANS) {
        float eta, den, v;
        v3 wh;
        if (same_side(wo, wi) || co == 0 || cii == 0) return f;
        eta = trans_eta(c, wo);
        wh = norm(add(wo, scale(wi, eta)));
        if (wh.z * wo.z < 0) wh = neg(wh); /* towards wo's side */
        if (dot(wo, wh) * dot(wi, wh) > 0) return f;
        /* the microfacet must face wo: where it does not, the sampler never goes */
        if (!is_bug("facing") && dot(wo, wh) <= 0) return f;
        den = dot(wo, wh) + eta * dot(wi, wh);
        v = tr_d(&c->d, wh) * tr_g(&c->d, wo, wi) * eta * eta * fabsf(dot(wi, wh)) * fabsf(dot(wo, wh)) /
            (co * cii * den * den);
        /* radiance transport: (eta_o / eta_i)^2 = 1 / eta^2 */
        v /= eta * eta;
        for (k = 0; k < 3; ++k) f.c[k] = c->r.c[k] * (1 - fr_dielectric(dot(wo, wh.z < 0 ? neg(wh) : wh), 1, c->ior)) * fabsf(v);
        return f;
    }
    if (c->kind == BLEND) {
        v3 wh;
        float dwo, dwi, sp;
        if (!same_side(wo, wi)) return f;
        dwo = 1 - powf(1 - .5f * cii, 5);
        dwi = 1 - powf(1 - .5f * co, 5);
        wh = add(wi, wo);
        if (wh.x == 0 && wh.y == 0 && wh.z == 0) return f;
        wh = norm(wh);
        for (k = 0; k < 3; ++k) {
            float rs = c->rs.c[k], sch = rs + powf(1 - fabsf(dot(wi, wh)), 5) * (1 - rs);
            sp = tr_d(&c->d, wh) / (4 * fabsf(dot(wi, wh)) * fmaxf(cii, co)) * sch;
            f.c[k] = (28.f / (23.f * PI_F)) * c->r.c[k] * (1 - rs) * dwo * dwi + sp;
        }
        return f;
    }
    return f; /* delta lobes */
}

/* The probability of choosing FresnelBlend's glossy half: Schlick's curve
 * of |cos theta_o|, in [0.25, 1]. */
static float blend_w(v3 wo) { return 0.25f + 0.75f * powf(1 - fabsf(wo.z), 5); }

/* The density of FresnelBlend's glossy half at wh. The bug guards the
 * division by cos theta_o at grazing with "if (c < 2e-4) c -= 2e-4" where
 * "c = 2e-4" was meant: below 2e-4 it is negative. */
static float blend_spec_pdf(const tr *d, v3 wo, v3 wh)
{
    float c = fabsf(wo.z);
    if (is_bug("blend-negative") && c < 2e-4f) c -= 2e-4f;
    return tr_d(d, wh) * tr_g1(d, wo) * fabsf(dot(wo, wh)) / c;
}

static float comp_pdf(const comp *c, v3 wo, v3 wi)
{
    if (c->kind == LAMBERT || c->kind == OREN) return same_side(wo, wi) ? fabsf(wi.z) / PI_F : 0;
    if (c->kind == MF_REFL) {
        v3 wh;
        if (!same_side(wo, wi)) return 0;
        wh = add(wo, wi);
        if (wh.x == 0 && wh.y == 0 && wh.z == 0) return 0;
        wh = norm(wh);
        return tr_pdf(&c->d, wo, wh) / (4 * fabsf(dot(wo, wh)));
    }
    if (c->kind == MF_TRANS) {
        float eta, den;
        v3 wh;
        if (same_side(wo, wi) || wo.z == 0 || wi.z == 0) return 0;
        eta = trans_eta(c, wo);
        wh = norm(add(wo, scale(wi, eta)));
        if (wh.z * wo.z < 0) wh = neg(wh);
        if (dot(wo, wh) * dot(wi, wh) > 0) return 0;
        if (!is_bug("facing") && dot(wo, wh) <= 0) return 0;
        den = dot(wo, wh) + eta * dot(wi, wh);
        return tr_pdf(&c->d, wo, wh) * fabsf(eta * eta * dot(wi, wh) / (den * den));
    }
    if (c->kind == BLEND) {
        v3 wh;
        float w = blend_w(wo);
        if (!same_side(wo, wi)) return 0;
        wh = add(wo, wi);
        if (wh.x == 0 && wh.y == 0 && wh.z == 0) return (1 - w) * fabsf(wi.z) / PI_F;
        wh = norm(wh);
        return (1 - w) * fabsf(wi.z) / PI_F + w * blend_spec_pdf(&c->d, wo, wh) / (4 * fabsf(dot(wo, wh)));
    }
    return 0;
}

static v3 cosine_hemisphere(float u1, float u2, v3 wo)
{
    float r = sqrtf(u1), phi = 2 * PI_F * u2;
    v3 w = mk(r * cosf(phi), r * sinf(phi), sqrtf(fmaxf(0, 1 - u1)));
    if (wo.z < 0) w.z = -w.z;
    return w;
}

static v3 reflect(v3 wo, v3 n) { return add(neg(wo), scale(n, 2 * dot(wo, n))); }

/* Refraction of wo through a surface of normal n (on wo's side), eta =
 * eta_o / eta_t: 0 at total internal reflection. */
static int refract(v3 wo, v3 n, float eta, v3 *wi)
{
    float ci = dot(n, wo), s2i = fmaxf(0, 1 - ci * ci), s2t = eta * eta * s2i, ct;
    if (s2t >= 1) return 0;
    ct = sqrtf(1 - s2t);
    *wi = add(scale(neg(wo), eta), scale(n, eta * ci - ct));
    return 1;
}

/* A component's sample from (u, v): wi, f (the component's own), pdf and
 * flags (a Fresnel lobe says which way it went). */
static int comp_sample(const comp *c, v3 wo, float u, float v, v3 *wi, rgb *f, float *pdf, unsigned *flags)
{
    int k;
    *flags = comp_flags(c);
    if (wo.z == 0) return 0;
    if (c->kind == LAMBERT || c->kind == OREN) {
        *wi = cosine_hemisphere(u, v, wo);
    } else if (c->kind == MF_REFL) {
        v3 wh = tr_sample(&c->d, wo, u, v);
        *wi = reflect(wo, wh);
        if (!same_side(wo, *wi)) return 0;
    } else if (c->kind == MF_TRANS) {
        v3 wh = tr_sample(&c->d, wo, u, v);
        if (dot(wo, wh) <= 0) return 0;
        if (!refract(wo, wh, 1 / trans_eta(c, wo), wi) || same_side(wo, *wi)) return 0;
    } else if (c->kind == BLEND) {
        float w = blend_w(wo);
        if (u < 1 - w) {
            *wi = cosine_hemisphere(fminf(u / (1 - w), ONE_MINUS_EPS), v, wo);
        } else {
            v3 wh = tr_sample(&c->d, wo, fminf((u - (1 - w)) / w, ONE_MINUS_EPS), v);
            *wi = reflect(wo, wh);
            if (!same_side(wo, *wi)) return 0;
        }
    } else if (c->kind == SPEC_REFL) {
        *wi = mk(-wo.x, -wo.y, wo.z);
        *pdf = 1;
        for (k = 0; k < 3; ++k) f->c[k] = c->r.c[k] / fabsf(wi->z);
        return 1;
    } else { /* FresnelSpecular: reflect with probability F */
        float F = fr_dielectric(wo.z, 1, c->ior), eta = trans_eta(c, wo);
        if (u < F) {
            *wi = mk(-wo.x, -wo.y, wo.z);
            *pdf = F;
            *flags = REFL | SPECULAR;
            for (k = 0; k < 3; ++k) f->c[k] = F * c->r.c[k] / fabsf(wi->z);
            return 1;
        }
        if (!refract(wo, mk(0, 0, wo.z > 0 ? 1 : -1), 1 / eta, wi)) return 0;
        *pdf = 1 - F;
        *flags = TRANS | SPECULAR;
        /* radiance: (eta_o / eta_i)^2 */
        for (k = 0; k < 3; ++k) f->c[k] = c->t.c[k] * (1 - F) / (eta * eta) / fabsf(wi->z);
        return 1;
    }
    *pdf = comp_pdf(c, wo, *wi);
    *f = comp_f(c, wo, *wi);
    return *pdf > 0;
}

/* ---- the BSDF at the shading point ------------------------------------------------ */
#define MAXC 4
static comp comps[MAXC];
static int ncomp;
static v3 ns = {0, 0, 1}, ss = {1, 0, 0}, ts = {0, 1, 0}, ng = {0, 0, 1}, dpdu = {1, 0, 0};

static void frame(void)
{
    ns = norm(ns);
    ss = norm(add(dpdu, scale(ns, -dot(dpdu, ns))));
    if (!(len(ss) > 0.5f)) ss = fabsf(ns.x) < 0.9f ? norm(cross(mk(1, 0, 0), ns)) : norm(cross(mk(0, 1, 0), ns));
    ts = cross(ns, ss);
}

static v3 to_local(v3 w) { return mk(dot(w, ss), dot(w, ts), dot(w, ns)); }
static v3 to_world(v3 w) { return add(add(scale(ss, w.x), scale(ts, w.y)), scale(ns, w.z)); }

/* pbrt-v3's BSDF::f: the components the geometric normal admits */
static rgb bsdf_f(v3 wow, v3 wiw)
{
    v3 wo = to_local(wow), wi = to_local(wiw);
    int reflect_g = dot(wiw, ng) * dot(wow, ng) > 0, i, k;
    rgb f = gray(0);
    if (wo.z == 0) return f;
    for (i = 0; i < ncomp; ++i) {
        unsigned fl = comp_flags(&comps[i]);
        if ((reflect_g && (fl & REFL)) || (!reflect_g && (fl & TRANS))) {
            rgb g = comp_f(&comps[i], wo, wi);
            for (k = 0; k < 3; ++k) f.c[k] += g.c[k];
        }
    }
    return f;
}

static float bsdf_pdf(v3 wow, v3 wiw)
{
    v3 wo = to_local(wow), wi = to_local(wiw);
    float p = 0;
    int i;
    if (!ncomp || wo.z == 0) return 0;
    for (i = 0; i < ncomp; ++i) p += comp_pdf(&comps[i], wo, wi);
    return p / ncomp;
}

static int bsdf_sample(v3 wow, float uc, float u1, v3 *wiw, rgb *f, float *pdf, unsigned *flags)
{
    int which, i;
    v3 wo = to_local(wow), wi;
    float ur;
    if (!ncomp) return 0;
    which = (int)(uc * ncomp);
    if (which > ncomp - 1) which = ncomp - 1;
    ur = fminf(uc * ncomp - which, ONE_MINUS_EPS); /* two random numbers: uc rescaled drives the component */
    if (!comp_sample(&comps[which], wo, ur, u1, &wi, f, pdf, flags) || !(*pdf > 0)) return 0;
    *wiw = to_world(wi);
    if (!(*flags & SPECULAR)) {
        if (ncomp > 1)
            for (i = 0, *pdf = 0; i < ncomp; ++i) *pdf += comp_pdf(&comps[i], wo, wi) / ncomp;
        *f = bsdf_f(wow, *wiw);
    } else if (ncomp > 1) {
        *pdf /= ncomp;
    }
    return *pdf > 0;
}

/* ---- statements ------------------------------------------------------------------- */
typedef struct param {
    char type[16], name[32];
    float v[3];
    int n;
    int str;
} param;

/* "type name" [values] or "type name" "string": 1 and p, 0 at the end, -1
 * when it is not a parameter. */
static int next_param(const char **s, param *p)
{
    const char *t = *s;
    char decl[64];
    int n = 0;
    while (isspace((unsigned char)*t)) t++;
    if (!*t) return 0;
    if (*t != '"') return -1;
    t++;
    while (*t && *t != '"' && n < 63) decl[n++] = *t++;
    decl[n] = 0;
    if (*t++ != '"' || sscanf(decl, "%15s %31s", p->type, p->name) != 2) return -1;
    while (isspace((unsigned char)*t)) t++;
    p->n = 0;
    p->str = 0;
    if (*t == '"' || (*t == '[' && strchr(t, '"') && strchr(t, '"') < strchr(t, ']'))) {
        p->str = 1;
        t = strchr(t, '"') + 1;
        t = strchr(t, '"');
        if (!t) return -1;
        t++;
        while (isspace((unsigned char)*t)) t++;
        if (*t == ']') t++;
    } else {
        int br = *t == '[';
        if (br) t++;
        for (;;) {
            char *e;
            float x;
            while (isspace((unsigned char)*t)) t++;
            if (br && *t == ']') {
                t++;
                break;
            }
            x = strtof(t, &e);
            if (e == t) {
                if (br) return -1;
                break;
            }
            if (p->n < 3) p->v[p->n] = x;
            p->n++;
            t = e;
            if (!br) break;
        }
    }
    *s = t;
    return 1;
}

static float to_alpha(float r) { return sqrtf(2 / (1 / fmaxf(r, 1e-6f) + 2)); }

static int material(const char *args, char *out, size_t n)
{
    char type[32];
    const char *s = args;
    param p;
    int r, k;
    float kd[3] = {.5f, .5f, .5f}, ks[3] = {.25f, .25f, .25f}, kr[3] = {1, 1, 1}, kt[3] = {1, 1, 1};
    float eta[3] = {0.2004f, 0.9240f, 1.1022f}, kk[3] = {3.9129f, 2.4528f, 2.1421f};
    float sigma = 0, rough = -1, ur = -1, vr = -1, ior = 1.5f;
    int kd_set = 0, kr_set = 0, ks_set = 0;
    while (isspace((unsigned char)*s)) s++;
    if (sscanf(s, "\"%31[^\"]\"", type) != 1) return snprintf(out, n, "error Material needs a type");
    s = strchr(s + 1, '"') + 1;
    while ((r = next_param(&s, &p)) > 0) {
        if (!strcmp(p.type, "texture")) return snprintf(out, n, "error unsupported: textures (\"%s\")", p.name);
        if (!strcmp(p.type, "spectrum")) return snprintf(out, n, "error unsupported: spectra (\"%s\")", p.name);
        if (p.str) continue;
        if (!strcmp(p.type, "rgb") || !strcmp(p.type, "color")) {
            float *dst = !strcmp(p.name, "Kd") ? (kd_set = 1, kd) : !strcmp(p.name, "Ks") ? (ks_set = 1, ks) :
                         !strcmp(p.name, "Kr") ? (kr_set = 1, kr) : !strcmp(p.name, "Kt") ? kt :
                         !strcmp(p.name, "eta") ? eta : !strcmp(p.name, "k") ? kk : NULL;
            if (!dst) continue;
            if (p.n != 3) return snprintf(out, n, "error parameter \"%s\" needs 3 values", p.name);
            for (k = 0; k < 3; ++k) dst[k] = p.v[k];
        } else if (!strcmp(p.type, "float") && p.n == 1) {
            if (!strcmp(p.name, "sigma")) sigma = p.v[0];
            if (!strcmp(p.name, "roughness")) rough = p.v[0];
            if (!strcmp(p.name, "uroughness")) ur = p.v[0];
            if (!strcmp(p.name, "vroughness")) vr = p.v[0];
            if (!strcmp(p.name, "index")) ior = p.v[0];
        }
    }
    if (r < 0) return snprintf(out, n, "error Material: a parameter it cannot read");
    memset(comps, 0, sizeof comps);
    ncomp = 0;
    if (!strcmp(type, "matte")) {
        comp *c = &comps[ncomp++];
        float s2 = (sigma * PI_F / 180) * (sigma * PI_F / 180);
        c->kind = sigma > 0 ? OREN : LAMBERT;
        for (k = 0; k < 3; ++k) c->r.c[k] = kd[k];
        c->A = 1 - s2 / (2 * (s2 + 0.33f));
        c->B = 0.45f * s2 / (s2 + 0.09f);
    } else if (!strcmp(type, "plastic")) {
        if (!kd_set) kd[0] = kd[1] = kd[2] = .25f;
        comps[0].kind = LAMBERT;
        for (k = 0; k < 3; ++k) comps[0].r.c[k] = kd[k];
        comps[1].kind = MF_REFL;
        comps[1].fresnel = FR_DIEL;
        comps[1].ior = 1.5f;
        for (k = 0; k < 3; ++k) comps[1].r.c[k] = ks[k];
        comps[1].d.ax = comps[1].d.ay = to_alpha(rough < 0 ? 0.1f : rough);
        ncomp = 2;
    } else if (!strcmp(type, "metal")) {
        comp *c = &comps[ncomp++];
        c->kind = MF_REFL;
        c->fresnel = FR_COND;
        c->r = gray(1);
        for (k = 0; k < 3; ++k) {
            c->eta.c[k] = eta[k];
            c->k.c[k] = kk[k];
        }
        c->d.ax = to_alpha(ur >= 0 ? ur : rough < 0 ? 0.01f : rough);
        c->d.ay = to_alpha(vr >= 0 ? vr : rough < 0 ? 0.01f : rough);
    } else if (!strcmp(type, "mirror")) {
        comp *c = &comps[ncomp++];
        c->kind = SPEC_REFL;
        for (k = 0; k < 3; ++k) c->r.c[k] = kr_set ? kr[k] : 0.9f;
    } else if (!strcmp(type, "glass")) {
        comp *c = &comps[ncomp++];
        c->kind = FRESNEL_SPEC;
        c->ior = ior;
        for (k = 0; k < 3; ++k) {
            c->r.c[k] = kr[k];
            c->t.c[k] = kt[k];
        }
    } else if (!strcmp(type, "substrate")) {
        comp *c = &comps[ncomp++];
        c->kind = BLEND;
        if (!ks_set) ks[0] = ks[1] = ks[2] = .5f;
        for (k = 0; k < 3; ++k) {
            c->r.c[k] = kd[k];
            c->rs.c[k] = ks[k];
        }
        c->d.ax = to_alpha(ur >= 0 ? ur : .1f);
        c->d.ay = to_alpha(vr >= 0 ? vr : .1f);
    } else if (!strcmp(type, "roughglass")) {
        float a = to_alpha(rough < 0 ? 0.01f : rough);
        comps[0].kind = MF_REFL;
        comps[0].fresnel = FR_DIEL;
        comps[1].kind = MF_TRANS;
        comps[0].ior = comps[1].ior = ior;
        for (k = 0; k < 3; ++k) {
            comps[0].r.c[k] = kr[k];
            comps[1].r.c[k] = kt[k];
        }
        comps[0].d.ax = comps[0].d.ay = comps[1].d.ax = comps[1].d.ay = a;
        ncomp = 2;
    } else {
        return snprintf(out, n, "error unsupported: material \"%s\"", type);
    }
    return snprintf(out, n, "ok");
}

static int at(const char *s, char *out, size_t n)
{
    char key[16];
    int used;
    v3 nn = ns, g = ng, du = dpdu;
    while (sscanf(s, " %15s%n", key, &used) == 1) {
        int want = !strcmp(key, "uv") || !strcmp(key, "duvdx") || !strcmp(key, "duvdy") ? 2 : !strcmp(key, "flip") ? 1 : 3;
        float v[3];
        int k, u2;
        s += used;
        for (k = 0; k < want; ++k) {
            if (sscanf(s, " %f%n", &v[k], &u2) != 1) return snprintf(out, n, "error at: \"%s\" needs %d numbers", key, want);
            s += u2;
        }
        if (!strcmp(key, "n")) nn = mk(v[0], v[1], v[2]);
        if (!strcmp(key, "ng")) g = mk(v[0], v[1], v[2]);
        if (!strcmp(key, "dpdu")) du = mk(v[0], v[1], v[2]);
    }
    ns = nn;
    ng = norm(g);
    dpdu = du;
    frame();
    return snprintf(out, n, "ok");
}

/* ---- the protocol ------------------------------------------------------------------ */
static int word(const char *s, const char *w)
{
    size_t n = strlen(w);
    return !strncmp(s, w, n) && (!s[n] || isspace((unsigned char)s[n]));
}

static int answer(const char *s, char *out, size_t n)
{
    float v[6];
    char extra;
    while (isspace((unsigned char)*s)) s++;
    if (!*s || *s == '#') return 0;
    if (word(s, "version")) return snprintf(out, n, "protocol 2 impl-other 1 precision float") > 0;
    if (word(s, "conventions")) return snprintf(out, n, "transport radiance sample-numbers 2") > 0;
    if (word(s, "mode")) return snprintf(out, n, "ok") > 0; /* its own model in both */
    if (word(s, "at")) return at(s + 2, out, n) > 0;
    if (word(s, "eval")) {
        rgb f;
        v3 a, b;
        if (sscanf(s + 4, "%f %f %f %f %f %f %c", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5], &extra) != 6)
            return snprintf(out, n, "error eval: needs wox woy woz wix wiy wiz") > 0;
        a = norm(mk(v[0], v[1], v[2]));
        b = norm(mk(v[3], v[4], v[5]));
        f = bsdf_f(a, b);
        return snprintf(out, n, "%.9g %.9g %.9g %.9g", f.c[0], f.c[1], f.c[2], bsdf_pdf(a, b)) > 0;
    }
    if (word(s, "sample")) {
        rgb f = gray(0);
        v3 wi = mk(0, 0, 0);
        float pdf = 0;
        unsigned fl = 0;
        if (sscanf(s + 6, "%f %f %f %f %f %f %c", &v[0], &v[1], &v[2], &v[3], &v[4], &v[5], &extra) != 6)
            return snprintf(out, n, "error sample: needs wox woy woz uc u1 u2") > 0;
        if (!bsdf_sample(norm(mk(v[0], v[1], v[2])), v[3], v[4], &wi, &f, &pdf, &fl))
            return snprintf(out, n, "0 0 0 0 0 0 0 0") > 0;
        return snprintf(out, n, "%.9g %.9g %.9g %.9g %.9g %.9g %.9g %u", wi.x, wi.y, wi.z, f.c[0], f.c[1], f.c[2], pdf, fl) > 0;
    }
    if (word(s, "rho") || word(s, "bssrdf") || word(s, "shading") || word(s, "texture"))
        return snprintf(out, n, "error unsupported: the query \"%.20s\"", s) > 0;
    if (word(s, "Material")) return material(s + 8, out, n) > 0;
    if (word(s, "Texture")) return snprintf(out, n, "error unsupported: textures") > 0;
    if (word(s, "MakeNamedMaterial") || word(s, "NamedMaterial"))
        return snprintf(out, n, "error unsupported: named materials") > 0;
    return snprintf(out, n, "error unsupported: the statement \"%.40s\"", s) > 0;
}

int main(int argc, char **argv)
{
    char line[65536], out[1024];
    if (argc > 1) bug = argv[1];
    frame();
    while (fgets(line, sizeof line, stdin)) {
        size_t l = strlen(line);
        while (l && (line[l - 1] == '\n' || line[l - 1] == '\r')) line[--l] = 0;
        if (answer(line, out, sizeof out)) t_answer_out(out);
    }
    fflush(stdout);
    return 0;
}
