/*
 * Which lobes each material adds when a parameter is black, as pbrt-v2's
 * GetBSDF decides at the release, e6f6334 (its materials directory): metal
 * adds its lobe whatever its parameters; matte, plastic, shinymetal and
 * substrate (since commit 4c20ad4), uber, glass, mirror, translucent,
 * subsurface and kdsubsurface leave out a lobe whose scale is black
 * (IsBlack, after the clamp from below) at the shading point; mix keeps
 * every component of both materials. A lobe left in or out changes the pdf (it averages over the
 * components) and which component a uComponent picks, so each case is told
 * apart by the pdf, the sampled direction and the sampled flags, through the
 * query protocol in both modes (none of this is an erratum: a black lobe
 * left in is unbiased).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "materia.h"
#include "materia/query.h"
#include "support/check.h"
#include "support/tquery.h"

#define WO "0 0.6 0.8"
#define WI "0.48 -0.36 0.8"
#define COS_WI 0.8
#define EVAL "eval " WO " " WI

static mt_query *q;
static const char *mode_name;

static int ask(const char *line, double *v, int n) { return t_query_ask(q, line, v, n); }

/* f (3) and pdf of EVAL for the material statement mat. */
static int eval_of(const char *mat, double e[4])
{
    return ask(mat, NULL, 0) && ask(EVAL, e, 4);
}

/* wi (3), f (3), pdf, flags of "sample WO uc 0.9 0.3". */
static int sample_of(const char *mat, double uc, double s[8])
{
    char line[128];
    snprintf(line, sizeof line, "sample " WO " %g 0.9 0.3", uc);
    return ask(mat, NULL, 0) && ask(line, s, 8);
}

static void name_of(char *buf, size_t n, const char *what)
{
    snprintf(buf, n, "lobes %s: %s", mode_name, what);
}

static void near(double got, double want, const char *what)
{
    char name[160];
    name_of(name, sizeof name, what);
    t_rel(got, want, 1e-5, 1e-6, name);
}

static void same_sample(const double *a, const double *b, const char *what)
{
    char name[160];
    int k, ok = a[7] == b[7];
    for (k = 0; k < 3; k++) ok = ok && fabs(a[k] - b[k]) <= 1e-5;
    ok = ok && t_reldiff(a[6], b[6], 1e-6) <= 1e-5;
    name_of(name, sizeof name, what);
    t_check(ok, name, "wi (%g %g %g) pdf %g flags %g, want (%g %g %g) pdf %g flags %g", a[0], a[1], a[2], a[6],
            a[7], b[0], b[1], b[2], b[6], b[7]);
}

static void flags_are(const double *s, int flags, double pdf, const char *what)
{
    char name[160];
    name_of(name, sizeof name, what);
    t_check((int)s[7] == flags && t_reldiff(s[6], pdf, 1e-6) <= 1e-5, name, "flags %g pdf %g, want %d and %g",
            s[7], s[6], flags, pdf);
}

static void failed(const double *s, const char *what)
{
    char name[160];
    name_of(name, sizeof name, what);
    t_check(s[6] == 0 && s[7] == 0 && s[0] == 0 && s[1] == 0 && s[2] == 0, name,
            "sampling should fail (no component): pdf %g flags %g", s[6], s[7]);
}

/* matte and shinymetal (pbrt-v2 commit 4c20ad4): no lobe for a black scale.
 * The 2012 source kept them: matte Kd 0 had pdf cos/pi and a Lambertian
 * sample, shinymetal Kr 0 an eta-1 conductor taking half the samples. */
static void matte_shinymetal(void)
{
    double d[4], e[4], sd[8], s[8];
    if (!eval_of("Material \"matte\"", d) || !sample_of("Material \"matte\"", 0.3, sd)) return;
    if (eval_of("Material \"matte\" \"rgb Kd\" [0 0 0]", e)) {
        near(e[3], 0, "matte Kd 0: no Lambertian, pdf 0");
        near(e[0], 0, "matte Kd 0: f 0");
    }
    if (sample_of("Material \"matte\" \"rgb Kd\" [0 0 0]", 0.3, s)) failed(s, "matte Kd 0");
    if (eval_of("Material \"matte\" \"rgb Kd\" [0 0 0] \"float sigma\" [30]", e))
        near(e[3], 0, "matte Kd 0 sigma 30: no Oren-Nayar, pdf 0");
    /* clamped from below first: a negative Kd is black too */
    if (sample_of("Material \"matte\" \"rgb Kd\" [-1 0 -0.5]", 0.3, s)) failed(s, "matte Kd negative");
    if (sample_of("Material \"matte\" \"rgb Kd\" [0 0 0.001]", 0.3, s))
        same_sample(s, sd, "matte Kd 0 0 0.001: a Lambertian (not black)");
    if (sample_of("Material \"matte\" \"float sigma\" [-5]", 0.3, s))
        same_sample(s, sd, "matte sigma -5: clamped to 0, Lambertian");

    if (!eval_of("Material \"shinymetal\"", d) || !sample_of("Material \"shinymetal\"", 0.3, sd)) return;
    if (eval_of("Material \"shinymetal\" \"rgb Kr\" [0 0 0]", e))
        near(e[3], 2 * d[3], "shinymetal Kr 0: the glossy lobe alone, pdf doubled");
    if (sample_of("Material \"shinymetal\" \"rgb Kr\" [0 0 0]", 0.7, s)) {
        flags_are(s, 9, 2 * sd[6], "shinymetal Kr 0: uc 0.7 glossy (no specular lobe)");
        near(s[0], sd[0], "shinymetal Kr 0: the glossy direction");
    }
    if (sample_of("Material \"shinymetal\" \"rgb Ks\" [0 0 0]", 0.3, s)) {
        flags_are(s, 17, 1, "shinymetal Ks 0: the specular lobe alone, pdf 1");
        near(s[1], -0.6, "shinymetal Ks 0: mirror direction");
    }
    if (eval_of("Material \"shinymetal\" \"rgb Ks\" [0 0 0]", e)) near(e[3], 0, "shinymetal Ks 0: no glossy pdf");
    if (sample_of("Material \"shinymetal\" \"rgb Kr\" [0 0 0] \"rgb Ks\" [0 0 0]", 0.7, s))
        failed(s, "shinymetal Kr 0 Ks 0");
}

/* plastic and substrate (pbrt-v2 commit 4c20ad4): plastic adds each lobe
 * only for a non-black scale, substrate its FresnelBlend unless Kd and Ks
 * are both black. (The 2012 source kept both of plastic's lobes and the
 * FresnelBlend whatever they were.) */
static void plastic_substrate(void)
{
    double d[4], e[4], c[4], sd[8], s[8], sm[8];
    const double lam = COS_WI / MT_PI;
    if (!eval_of("Material \"plastic\"", d) || !sample_of("Material \"plastic\"", 0.7, sd) ||
        !sample_of("Material \"matte\"", 0.3, sm))
        return;
    if (eval_of("Material \"plastic\" \"rgb Kd\" [0 0 0]", e)) {
        /* the mean of two pdfs becomes the coat's own */
        near(e[3], 2 * d[3] - lam, "plastic Kd 0: the coat's pdf alone");
        near(e[0], d[0] - 0.25 / MT_PI, "plastic Kd 0: f is the coat's");
    }
    if (sample_of("Material \"plastic\" \"rgb Kd\" [0 0 0]", 0.3, s)) {
        char name[160];
        name_of(name, sizeof name, "plastic Kd 0: uc 0.3 samples the coat (no Lambertian)");
        t_check((int)s[7] == 9, name, "flags %g, want 9", s[7]);
    }
    if (sample_of("Material \"plastic\" \"rgb Kd\" [0 0 0]", 0.7, s))
        flags_are(s, 9, 2 * sd[6] - sd[2] / MT_PI, "plastic Kd 0: uc 0.7 the coat, pdf its own");
    if (eval_of("Material \"plastic\" \"rgb Ks\" [0 0 0]", e)) near(e[3], lam, "plastic Ks 0: the Lambertian's pdf alone");
    if (sample_of("Material \"plastic\" \"rgb Ks\" [0 0 0]", 0.7, s)) {
        flags_are(s, 5, sm[6], "plastic Ks 0: uc 0.7 the Lambertian");
        near(s[1], sm[1], "plastic Ks 0: the Lambertian's direction");
    }
    if (eval_of("Material \"plastic\" \"rgb Kd\" [0 0 0] \"rgb Ks\" [0 0 0]", e)) {
        near(e[3], 0, "plastic Kd 0 Ks 0: no lobe, pdf 0");
        near(e[0], 0, "plastic Kd 0 Ks 0: f 0");
    }
    if (sample_of("Material \"plastic\" \"rgb Kd\" [0 0 0] \"rgb Ks\" [0 0 0]", 0.5, s))
        failed(s, "plastic Kd 0 Ks 0");

    if (!eval_of("Material \"substrate\"", d) || !sample_of("Material \"substrate\"", 0.3, sd)) return;
    if (eval_of("Material \"substrate\" \"rgb Kd\" [0 0 0] \"rgb Ks\" [0 0 0]", e)) {
        near(e[3], 0, "substrate Kd 0 Ks 0: no FresnelBlend, pdf 0");
        near(e[0], 0, "substrate Kd 0 Ks 0: f 0");
    }
    if (sample_of("Material \"substrate\" \"rgb Kd\" [0 0 0] \"rgb Ks\" [0 0 0]", 0.3, s))
        failed(s, "substrate Kd 0 Ks 0");
    /* one of the two is enough to keep it */
    if (eval_of("Material \"substrate\" \"rgb Kd\" [0 0 0]", c)) near(c[3], d[3], "substrate Kd 0: FresnelBlend kept");
    if (sample_of("Material \"substrate\" \"rgb Ks\" [0 0 0]", 0.3, s))
        same_sample(s, sd, "substrate Ks 0: FresnelBlend sample");
}

/* uber: each of its lobes only when its scale (times opacity) is not black. */
static void uber(void)
{
    double p[4], e[4], s[8];
    const double lam = COS_WI / MT_PI;
    if (!eval_of("Material \"plastic\"", p)) return;
    /* plastic's two lobes have uber's default pdfs (Lambertian, Blinn 10) */
    if (eval_of("Material \"uber\"", e)) near(e[3], p[3], "uber default: Lambertian and Blinn");
    if (eval_of("Material \"uber\" \"rgb Kd\" [0 0 0]", e)) near(e[3], 2 * p[3] - lam, "uber Kd 0: Blinn alone");
    if (sample_of("Material \"uber\" \"rgb Kd\" [0 0 0]", 0.3, s)) flags_are(s, 9, s[6], "uber Kd 0: uc 0.3 glossy");
    if (eval_of("Material \"uber\" \"rgb Ks\" [0 0 0]", e)) near(e[3], lam, "uber Ks 0: Lambertian alone");
    if (sample_of("Material \"uber\" \"rgb Ks\" [0 0 0]", 0.7, s)) flags_are(s, 5, s[2] / MT_PI, "uber Ks 0: uc 0.7 diffuse, pdf cos/pi");
    if (eval_of("Material \"uber\" \"rgb Kd\" [0 0 0] \"rgb Ks\" [0 0 0]", e)) near(e[3], 0, "uber Kd 0 Ks 0: no lobe");
    if (sample_of("Material \"uber\" \"rgb Kd\" [0 0 0] \"rgb Ks\" [0 0 0]", 0.5, s)) failed(s, "uber Kd 0 Ks 0");
    if (eval_of("Material \"uber\" \"rgb Kr\" [0.5 0.5 0.5]", e)) near(e[3], p[3] * 2 / 3, "uber Kr: a third lobe");
    if (eval_of("Material \"uber\" \"rgb opacity\" [0.5 0.5 0.5]", e))
        near(e[3], p[3] * 2 / 3, "uber opacity 0.5: transmission lobe added");
    if (sample_of("Material \"uber\" \"rgb opacity\" [0 0 0]", 0.3, s)) {
        flags_are(s, 18, 1, "uber opacity 0: transmission alone");
        near(s[2], -0.8, "uber opacity 0: straight through");
    }
    /* a texture black at some points: the lobe is there or not point by point */
    if (ask("Texture \"half\" \"color\" \"checkerboard\" \"float uscale\" [2] \"rgb tex1\" [0 0 0] \"rgb tex2\" [0.5 0.5 0.5]", NULL, 0) &&
        ask("at uv 0.25 0.25", NULL, 0) && eval_of("Material \"uber\" \"texture Kd\" \"half\"", e))
        near(e[3], 2 * p[3] - lam, "uber textured Kd black here: Blinn alone");
    if (ask("at uv 0.75 0.25", NULL, 0) && ask(EVAL, e, 4)) near(e[3], p[3], "uber textured Kd grey here: two lobes");
    if (eval_of("Material \"plastic\" \"texture Kd\" \"half\"", e) && ask("at uv 0.25 0.25", NULL, 0) && ask(EVAL, e, 4))
        near(e[3], 2 * p[3] - lam, "plastic textured Kd black here: the coat alone");
    if (ask("at uv 0.75 0.25", NULL, 0) && ask(EVAL, e, 4)) near(e[3], p[3], "plastic textured Kd grey here: two lobes");
    if (eval_of("Material \"matte\" \"texture Kd\" \"half\"", e) && ask("at uv 0.25 0.25", NULL, 0) && ask(EVAL, e, 4))
        near(e[3], 0, "matte textured Kd black here: no lobe");
    ask("at uv 0.5 0.5", NULL, 0);
}

static void specular(void)
{
    double e[4], s[8];
    if (sample_of("Material \"glass\" \"rgb Kr\" [0 0 0]", 0.3, s)) flags_are(s, 18, 1, "glass Kr 0: transmission alone");
    if (sample_of("Material \"glass\" \"rgb Kt\" [0 0 0]", 0.7, s)) flags_are(s, 17, 1, "glass Kt 0: reflection alone");
    if (sample_of("Material \"glass\" \"rgb Kr\" [0 0 0] \"rgb Kt\" [0 0 0]", 0.5, s)) failed(s, "glass Kr 0 Kt 0");
    if (sample_of("Material \"glass\"", 0.3, s)) flags_are(s, 17, 0.5, "glass: two lobes");
    if (sample_of("Material \"mirror\" \"rgb Kr\" [0 0 0]", 0.5, s)) failed(s, "mirror Kr 0");
    if (sample_of("Material \"subsurface\" \"rgb Kr\" [0 0 0]", 0.5, s)) failed(s, "subsurface Kr 0");
    if (sample_of("Material \"kdsubsurface\" \"rgb Kr\" [0 0 0]", 0.5, s)) failed(s, "kdsubsurface Kr 0");
    if (sample_of("Material \"metal\" \"float roughness\" [0]", 0.5, s))
        flags_are(s, 9, s[6], "metal roughness 0: its lobe kept (Blinn exponent capped)");
    if (eval_of("Material \"metal\" \"rgb eta\" [0 0 0] \"rgb k\" [0 0 0]", e))
        near(e[3] > 0, 1, "metal eta 0 k 0: its lobe kept");
}

/* translucent: each lobe only when its two scales are not black; no index. */
static void translucent(void)
{
    double d[4], e[4], s[8];
    if (sample_of("Material \"translucent\" \"rgb reflect\" [0 0 0]", 0.3, s))
        flags_are(s, 6, s[6], "translucent reflect 0: uc 0.3 the diffuse transmission");
    if (sample_of("Material \"translucent\" \"rgb Kd\" [0 0 0]", 0.3, s))
        flags_are(s, 9, s[6], "translucent Kd 0: uc 0.3 the glossy reflection");
    if (sample_of("Material \"translucent\" \"rgb Kd\" [0 0 0]", 0.7, s))
        flags_are(s, 10, s[6], "translucent Kd 0: uc 0.7 the glossy transmission");
    if (sample_of("Material \"translucent\" \"rgb reflect\" [0 0 0] \"rgb transmit\" [0 0 0]", 0.5, s))
        failed(s, "translucent reflect 0 transmit 0");
    if (sample_of("Material \"translucent\" \"rgb Kd\" [0 0 0] \"rgb Ks\" [0 0 0]", 0.5, s))
        failed(s, "translucent Kd 0 Ks 0");
    /* pbrt-v2's translucent reads no "index": its index is always 1.5 */
    if (eval_of("Material \"translucent\"", d) && eval_of("Material \"translucent\" \"float index\" [3]", e))
        near(e[0], d[0], "translucent index ignored");
}

/* A mix counts the lobes its materials can add: a constant black scale
 * adds none anywhere, so two default ubers (4 lobes) are a valid mix; two
 * whose opacity and Kr, Kt are textures could reach 10, past the BSDF's 8
 * (erratum mix-overflow: pbrt-v2 writes past its array), and are refused. */
static void mix_bound(void)
{
    double e[4];
    char out[512];
    if (ask("MakeNamedMaterial \"u\" \"string type\" [\"uber\"]", NULL, 0) &&
        eval_of("Material \"mix\" \"string namedmaterial1\" \"u\" \"string namedmaterial2\" \"u\"", e))
        near(e[3] > 0, 1, "mix of two default ubers: made (4 lobes)");
    if (!ask("Texture \"tk\" \"color\" \"uv\"", NULL, 0) ||
        !ask("MakeNamedMaterial \"ut\" \"string type\" [\"uber\"] \"texture Kr\" \"tk\" \"texture Kt\" \"tk\" "
             "\"texture opacity\" \"tk\"", NULL, 0))
        return;
    mt_query_line(q, "Material \"mix\" \"string namedmaterial1\" \"ut\" \"string namedmaterial2\" \"ut\"", out,
                  sizeof out);
    {
        char name[160];
        name_of(name, sizeof name, "mix of two textured ubers (up to 10 lobes): an error");
        t_check(!strncmp(out, "error", 5) && strstr(out, "10 BxDFs"), name, "%s", out);
    }
}

/* No "bumpmap", no bump mapping (pbrt-v2 commits bab4b9b, 67a83eb): the
 * shading normal stays the shape's even where it faces away from the
 * geometric normal. The 2012 source bump-mapped every material with a
 * constant 0, which turned it to the geometric normal's side: shinymetal's
 * shading normal would be -z here, and glass would see wo from inside. */
static void no_bump(void)
{
    double sh[9], s[8];
    char name[160];
    if (!ask("at ng 0 0 -1", NULL, 0)) return;
    if (ask("Material \"shinymetal\"", NULL, 0) && ask("shading", sh, 9)) {
        name_of(name, sizeof name, "shinymetal without a bump map: the shading normal as given, facing away from ng");
        t_check(sh[2] == 1 && sh[0] == 0 && sh[1] == 0, name, "n %g %g %g", sh[0], sh[1], sh[2]);
    }
    /* glass, uc 0.7: the transmission, entering from +z with eta 1/1.5 */
    if (sample_of("Material \"glass\"", 0.7, s)) {
        near(s[1], -0.4, "glass without a bump map, ng facing away: wo enters (y of wi)");
        near(s[2], -sqrt(1 - 0.16), "glass without a bump map, ng facing away: wo enters (z of wi)");
    }
    ask("at ng 0 0 1", NULL, 0);
}

/* A dpdu not perpendicular to the normal: pbrt-v2's frame is sn =
 * normalize(dpdu), tn = nn x sn (erratum bsdf-frame), not orthonormal, so
 * local directions have different lengths, and Microfacet::f takes
 * Dot(wi, wh) for the Fresnel term and AbsDot(wo, wh) in G, which then
 * differ (|wo + wi| / 2, their common value for directions of one length,
 * is below the coat's critical cosine here, Dot(wi, wh) above it: F = 1
 * against 0.05). Expected f from pbrt-v2's formulas: plastic's coat alone
 * (Kd 0), Ks 0.5, Blinn exponent 10, FresnelDielectric(1.5, 1). */
static void oblique_frame(void)
{
    static const double sn[3] = {0.8, 0, 0.6}, tn[3] = {0, 0.8, 0}, wow[3] = {-0.9, 0, 0.436},
                        wiw[3] = {0.9, 0, 0.436};
    double wo[3], wi[3], h[3], l, e[4], D, G, cosh_i, cosh_o, want, sym;
    mt_fresnel fr = mt_fresnel_dielectric(1.5f, 1);
    int k;
    char name[160];
    if (strcmp(mode_name, "pbrt-v2") != 0) return; /* corrected mode's frame is orthonormal */
    {
        wo[0] = sn[0] * wow[0] + sn[1] * wow[1] + sn[2] * wow[2];
        wo[1] = tn[0] * wow[0] + tn[1] * wow[1] + tn[2] * wow[2];
        wo[2] = wow[2];
        wi[0] = sn[0] * wiw[0] + sn[1] * wiw[1] + sn[2] * wiw[2];
        wi[1] = tn[0] * wiw[0] + tn[1] * wiw[1] + tn[2] * wiw[2];
        wi[2] = wiw[2];
    }
    for (k = 0; k < 3; k++) h[k] = wo[k] + wi[k];
    l = sqrt(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
    for (k = 0; k < 3; k++) h[k] /= l;
    cosh_i = wi[0] * h[0] + wi[1] * h[1] + wi[2] * h[2];
    cosh_o = fabs(wo[0] * h[0] + wo[1] * h[1] + wo[2] * h[2]);
    D = 12 / (2 * MT_PI) * pow(h[2], 10);
    G = fmin(1, fmin(2 * h[2] * wo[2] / cosh_o, 2 * h[2] * wi[2] / cosh_o));
    want = 0.5 * D * G * mt_fresnel_evaluate(&fr, (mt_real)cosh_i).c[0] / (4 * wi[2] * wo[2]);
    sym = 0.5 * D * fmin(1, fmin(2 * h[2] * wo[2] / (l / 2), 2 * h[2] * wi[2] / (l / 2))) *
          mt_fresnel_evaluate(&fr, (mt_real)(l / 2)).c[0] / (4 * wi[2] * wo[2]);
    if (ask("at dpdu 0.8 0 0.6", NULL, 0) &&
        eval_of("Material \"plastic\" \"rgb Kd\" [0 0 0] \"rgb Ks\" [0.5 0.5 0.5]", e) &&
        ask("eval -0.9 0 0.436 0.9 0 0.436", e, 4)) {
        near(e[0], want, "oblique dpdu: the coat's f with pbrt-v2's Dot(wi, wh) and AbsDot(wo, wh)");
        name_of(name, sizeof name, "oblique dpdu: the two cosines differ enough to tell the formulas apart");
        t_check(fabs(sym - want) > 0.01 * want, name, "%g vs %g", sym, want);
    }
    ask("at dpdu 1 0 0", NULL, 0);
}

/* mix: every component of both, scaled, even by 0. */
static void mix(void)
{
    double s[8];
    if (!ask("MakeNamedMaterial \"a\" \"string type\" [\"matte\"]", NULL, 0) ||
        !ask("MakeNamedMaterial \"b\" \"string type\" [\"plastic\"] \"rgb Kd\" [0 0 0]", NULL, 0))
        return;
    if (sample_of("Material \"mix\" \"string namedmaterial1\" \"a\" \"string namedmaterial2\" \"b\" \"rgb amount\" [0 0 0]",
                  0.2, s)) {
        char name[160];
        name_of(name, sizeof name, "mix amount 0: the first material's lobe kept, scaled by 0");
        t_check((int)s[7] == 5, name, "flags %g", s[7]);
    }
    if (sample_of("Material \"mix\" \"string namedmaterial1\" \"a\" \"string namedmaterial2\" \"b\" \"rgb amount\" [0 0 0]",
                  0.5, s)) {
        char name[160];
        /* plastic Kd 0 has its coat alone: matte's Lambertian and the coat */
        name_of(name, sizeof name, "mix amount 0: plastic Kd 0 brings its coat alone");
        t_check((int)s[7] == 9, name, "flags %g", s[7]);
    }
}

int main(void)
{
    static const char *modes[] = {"pbrt-v2", "corrected"};
    int m;
    for (m = 0; m < 2; m++) {
        mt_error err;
        char line[32];
        q = mt_query_create(NULL, &err);
        if (!q) {
            t_fail("lobes: session", "%s", err.message);
            break;
        }
        mode_name = modes[m];
        snprintf(line, sizeof line, "mode %s", mode_name);
        if (ask(line, NULL, 0)) {
            matte_shinymetal();
            plastic_substrate();
            uber();
            specular();
            translucent();
            mix();
            mix_bound();
            no_bump();
            oblique_frame();
        }
        mt_query_destroy(q);
    }
    return t_status();
}
