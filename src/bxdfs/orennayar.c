/*
 * Oren-Nayar diffuse reflection, pbrt-v2's qualitative model (reflection.h/.cpp
 * OrenNayar; Oren and Nayar 1994): f = R/pi (A + B max(0, cos(phi_i - phi_o))
 * sin(alpha) tan(beta)), with sigma given in degrees.
 */
#include "bxdfs/kinds.h"

typedef struct orennayar {
    mt_bxdf base;
    mt_rgb R;
    mt_real A, B;
} orennayar;

static mt_rgb orennayar_f(const mt_bxdf *b, mt_vec3 wo, mt_vec3 wi)
{
    const orennayar *o = (const orennayar *)b;
    mt_real sinthetai = mt_sin_theta(wi), sinthetao = mt_sin_theta(wo);
    mt_real maxcos = 0, sinalpha, tanbeta, cosi = mt_abs_cos_theta(wi),
            coso = mt_abs_cos_theta(wo);
    if (sinthetai > 1e-4 && sinthetao > 1e-4) {
        mt_real sinphii = mt_sin_phi(wi), cosphii = mt_cos_phi(wi);
        mt_real sinphio = mt_sin_phi(wo), cosphio = mt_cos_phi(wo);
        mt_real dcos = cosphii * cosphio + sinphii * sinphio;
        maxcos = mt_max(0, dcos);
    }
    if (cosi > coso) {
        sinalpha = sinthetao;
        tanbeta = sinthetai / cosi;
    } else if (coso > 0) {
        sinalpha = sinthetai;
        tanbeta = sinthetao / coso;
    } else {
        /* Both directions exactly grazing: pbrt-v2 divides by zero (0 * Inf
         * is NaN). They carry no energy; the B term is dropped. */
        return mt_rgb_scale(o->R, MT_INV_PI * o->A);
    }
    return mt_rgb_scale(mt_rgb_scale(o->R, MT_INV_PI), o->A + o->B * maxcos * sinalpha * tanbeta);
}

static const mt_bxdf_ops orennayar_ops = {
    .name = "orennayar",
    .f = orennayar_f,
    .sample_f = mt_bxdf_default_sample_f,
    .pdf = mt_bxdf_default_pdf,
    .rho_hd = mt_bxdf_default_rho_hd,
    .rho_hh = mt_bxdf_default_rho_hh,
};

mt_bxdf *mt_orennayar_create(mt_arena *a, mt_mode mode, mt_rgb R, mt_real sigma_deg,
                             mt_error *err)
{
    orennayar *o;
    mt_real sigma, sigma2;
    mt_error_clear(err);
    if (!mt__check_rgb(R, "R", "orennayar", err) ||
        !mt__check_real(sigma_deg, "sigma", "orennayar", err))
        return NULL;
    o = mt__bxdf_alloc(a, sizeof *o, &orennayar_ops, MT_BSDF_REFLECTION | MT_BSDF_DIFFUSE, mode,
                       err);
    if (!o) return NULL;
    sigma = mt_radians(sigma_deg);
    sigma2 = sigma * sigma;
    o->R = R;
    o->A = 1 - (sigma2 / (2 * (sigma2 + (mt_real)0.33)));
    o->B = (mt_real)0.45 * sigma2 / (sigma2 + (mt_real)0.09);
    return &o->base;
}
