/*
 * metal (pbrt-v2 metal.cpp): a Blinn microfacet conductor. The default eta and
 * k are pbrt-v2's copper, sampled at 56 wavelengths and converted to RGB as
 * pbrt-v2 does (Spectrum::FromSampled); the samples are physical data (the
 * complex index of copper) as pbrt-v2's metal.cpp tabulates them.
 */
#include <pthread.h>
#include "materials/material_impl.h"
#include "materia/spectrum.h"

enum { ETA, K, ROUGHNESS };

#define NCU 56
static const double cu_lambda[NCU] = {
    298.7570554, 302.4004341, 306.1337728, 309.960445,  313.8839949, 317.9081487, 322.036826,
    326.2741526, 330.6244747, 335.092373,  339.6826795, 344.4004944, 349.2512056, 354.2405086,
    359.374429,  364.6593471, 370.1020239, 375.7096303, 381.4897785, 387.4505563, 393.6005651,
    399.9489613, 406.5055016, 413.2805933, 420.2853492, 427.5316483, 435.0322035, 442.8006357,
    450.8515564, 459.2006593, 467.8648226, 476.8622231, 486.2124627, 495.936712,  506.0578694,
    516.6007417, 527.5922468, 539.0616435, 551.0407911, 563.5644455, 576.6705953, 590.4008476,
    604.8008683, 619.92089,   635.8162974, 652.5483053, 670.1847459, 688.8009889, 708.4810171,
    729.3186941, 751.4192606, 774.9011125, 799.8979226, 826.5611867, 855.0632966, 885.6012714};
static const double cu_n[NCU] = {
    1.400313, 1.38,     1.358438, 1.34,     1.329063, 1.325,    1.3325,   1.34,     1.334375, 1.325,
    1.317812, 1.31,     1.300313, 1.29,     1.281563, 1.27,     1.249062, 1.225,    1.2,      1.18,
    1.174375, 1.175,    1.1775,   1.18,     1.178125, 1.175,    1.172812, 1.17,     1.165312, 1.16,
    1.155312, 1.15,     1.142812, 1.135,    1.131562, 1.12,     1.092437, 1.04,     0.950375, 0.826,
    0.645875, 0.468,    0.35125,  0.272,    0.230813, 0.214,    0.20925,  0.213,    0.21625,  0.223,
    0.2365,   0.25,     0.254188, 0.26,     0.28,     0.3};
static const double cu_k[NCU] = {
    1.662125, 1.687,    1.703313, 1.72,     1.744563, 1.77,     1.791625, 1.81,     1.822125, 1.834,
    1.85175,  1.872,    1.89425,  1.916,    1.931688, 1.95,     1.972438, 2.015,    2.121562, 2.21,
    2.177188, 2.13,     2.160063, 2.21,     2.249938, 2.289,    2.326,    2.362,    2.397625, 2.433,
    2.469187, 2.504,    2.535875, 2.564,    2.589625, 2.605,    2.595562, 2.583,    2.5765,   2.599,
    2.678062, 2.809,    3.01075,  3.24,     3.458187, 3.67,     3.863125, 4.05,     4.239563, 4.43,
    4.619563, 4.817,    5.034125, 5.26,     5.485625, 5.717};

static int metal_max(const mt_material *m) { return 1; }

static mt_status metal_add(const mt_material *m, mt_bsdf *b, const mt_diffgeom *dgs, mt_arena *a, mt_error *err)
{
    /* pbrt-v2 does not clamp eta and k */
    mt_rgb eta = mt_texture_eval_rgb(m->tex[ETA], dgs), k = mt_texture_eval_rgb(m->tex[K], dgs);
    mt_real rough = MT_FLOAT(m, ROUGHNESS, dgs);
    return mt__bsdf_add(b, mt_microfacet_create(a, m->mode, mt_rgb_gray(1), mt_fresnel_conductor(eta, k),
                                                mt_blinn(1 / rough), err),
                        err);
}

/* eta and k default to copper's (metal_defaults) */
static const mt_tex_slot metal_slots[] = {
    {"eta", 0, {0}, MT_RANGE_NONNEG, "real part of the conductor's index of refraction (default: copper)"},
    {"k", 0, {0}, MT_RANGE_NONNEG, "absorption coefficient, the imaginary part (default: copper)"},
    {"roughness", 1, {0.01f}, MT_RANGE_NONNEG, "the Blinn exponent is 1/roughness (at most 10000)"}};

/* Copper as RGB, converted once: pbrt-v2's CreateMetalMaterial converts the
 * sampled copper again for every metal it creates, and a scene creates one
 * per Shape statement (real-metal-teapot's 2256 shapes: 4512 conversions of
 * 471 interpolated wavelengths each, 30% of the instructions of a 4-spp
 * render). The result depends on the constants above alone. */
static mt_rgb cu_n_rgb, cu_k_rgb;
static pthread_once_t cu_once = PTHREAD_ONCE_INIT;

static void cu_convert(void)
{
    cu_n_rgb = mt_spectrum_from_sampled(cu_lambda, cu_n, NCU);
    cu_k_rgb = mt_spectrum_from_sampled(cu_lambda, cu_k, NCU);
}

static void metal_defaults(mt_tex_slot *s)
{
    mt_rgb n, k;
    int c;
    pthread_once(&cu_once, cu_convert);
    n = cu_n_rgb;
    k = cu_k_rgb;
    for (c = 0; c < 3; ++c) {
        s[ETA].def[c] = n.c[c];
        s[K].def[c] = k.c[c];
    }
}

const mt_material_kind mt_metal_material = {
    .type = "metal",
    .max_bxdfs = metal_max,
    .add_bxdfs = metal_add,
    .slots = metal_slots,
    .nslots = MT_COUNT(metal_slots),
    .defaults = metal_defaults,
};

