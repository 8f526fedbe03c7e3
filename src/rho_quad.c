/*
 * Reflectance by quadrature: BxDF::rho's estimand (the hemispherical-
 * directional reflectance) computed by adaptive cubature instead of Monte
 * Carlo, for the query tool and the conformance suite's furnace.
 *
 * The hemisphere is cut into cells in (phi, cos theta), where the solid angle
 * is dphi dz. A quadrature can only find mass its nodes see; a Blinn lobe of
 * exponent 10^4 is 0.02 rad wide. The BxDF's own sampler is therefore asked
 * where its mass lies, and the cells its samples land in start from a grid
 * fine enough for the narrowest lobe. The sampler only steers the effort: the
 * value is the integral of f.
 *
 * Each cell's refinement is capped at eight times its initial work: in the
 * float build f itself is noisy (pbrt-v2's D = cos^e at e = 10^4 carries
 * e * 6e-8 relative rounding noise), and no refinement converges below that.
 *
 * A measured BxDF's f is a table lookup, discontinuous along curves that
 * cross nearly every cell (MERL bins; the irregular reader's set of samples
 * within the search radius): a Gauss-Kronrod rule never converges there,
 * every cell spends its whole cap, and the refinement moves the value about
 * as much as the error it can reach. Its cells get their initial work only.
 * Measured with `materia-query --dir ../shared/reference/scenes`, rho 0 0.6
 * 0.8 of "brdfs/mystique.brdf": 2,133,900 evaluations (1.6 s on a loaded
 * machine) become 274,500 (0.26 s); the first channel moves from 0.0401091
 * to 0.0401819 (+0.18%), against 0.0401107 with 64 times the work (cap 2
 * and 4 give 0.0401867 and 0.0402259: refinement does not converge); a
 * plastic MERL table made by materia-merl moves by 2e-5 relative.
 */
#include "materia/tools/cubature.h"
#include "measured/measured_impl.h"

/* The fuzzing build (make fuzz) sets a coarser grid, no refinement and no
 * finer start in the cells the sampler points at: each cell's work has a
 * floor (one 15 x 15 rule per grid cell, 115,200 evaluations per component
 * at 32 x 16), a cell holding a peak starts on a grid up to MT_RHO_MAX_GRID
 * on a side (up to 64 times that floor), refinement multiplies it up to
 * MT_RHO_WORK times, and there the code paths matter, not the value. */
#ifndef MT_RHO_NPHI
#define MT_RHO_NPHI 32
#endif
#ifndef MT_RHO_NZ
#define MT_RHO_NZ 16
#endif
#ifndef MT_RHO_WORK
#define MT_RHO_WORK 8 /* the refinement cap (top of the file) */
#endif
#ifndef MT_RHO_MAX_GRID
#define MT_RHO_MAX_GRID 8 /* mt_cubature_grid's largest: no cap */
#endif
#define NPHI MT_RHO_NPHI
#define NZ MT_RHO_NZ
#define NHINT 24 /* a 24 x 24 grid of sampler calls */

typedef struct rho_ctx {
    const mt_bxdf *b;
    mt_vec3 wo;
    double zsign;
} rho_ctx;

static void rho_integrand(void *ctx, double phi, double z, double *out)
{
    const rho_ctx *c = ctx;
    mt_vec3 wi = mt_sphere_direction(phi, c->zsign * z);
    mt_rgb f = c->b->ops->f(c->b, c->wo, wi);
    out[0] = f.c[0] * z;
    out[1] = f.c[1] * z;
    out[2] = f.c[2] * z;
}

static mt_rgb delta_weight(const mt_bxdf *b, mt_vec3 wo)
{
    mt_vec3 wi;
    mt_real pdf = 0;
    mt_rgb f = b->ops->sample_f(b, wo, &wi, (mt_real)0.5, (mt_real)0.5, &pdf);
    if (!(pdf > 0)) return mt_rgb_black();
    return mt_rgb_scale(f, mt_abs_cos_theta(wi) / pdf);
}

mt_rgb mt_bxdf_rho_quad(const mt_bxdf *b, mt_vec3 wo, double rel_tol)
{
    int hits[NPHI][NZ] = {{0}}, nhits = 0;
    double sum[3] = {0, 0, 0}, scale = 0;
    rho_ctx c;
    long work = mt__bxdf_is_measured(b) ? 1 : MT_RHO_WORK;
    int i, j, k;
    if (b->type & MT_BSDF_SPECULAR) return delta_weight(b, wo);
    c.b = b;
    c.wo = wo;
    /* the hemisphere the component scatters into, as its sampler chooses it */
    c.zsign = (wo.z >= 0) == !(b->type & MT_BSDF_TRANSMISSION) ? 1 : -1;
    for (i = 0; i < NHINT; ++i)
        for (j = 0; j < NHINT; ++j) {
            mt_vec3 wi;
            mt_real pdf = 0;
            mt_rgb f = b->ops->sample_f(b, wo, &wi, (mt_real)((i + 0.5) / NHINT),
                                        (mt_real)((j + 0.5) / NHINT), &pdf);
            double z = c.zsign * wi.z, phi;
            if (!(pdf > 0) || !(z >= 0)) continue;
            phi = atan2(wi.y, wi.x);
            if (phi < 0) phi += 2 * 3.14159265358979323846;
            hits[(int)(phi / (2 * 3.14159265358979323846) * NPHI) % NPHI][z >= 1 ? NZ - 1 : (int)(z * NZ)]++;
            nhits++;
            scale = fmax(scale, mt_rgb_max(f) * z / pdf / (NHINT * NHINT));
        }
    for (i = 0; i < NPHI; ++i)
        for (j = 0; j < NZ; ++j) {
            mt_cubature_result r;
            double p0 = 2 * 3.14159265358979323846 * i / NPHI, p1 = 2 * 3.14159265358979323846 * (i + 1) / NPHI;
            int sub = nhits ? mt_cubature_grid((double)hits[i][j] * NPHI * NZ / nhits) : 1;
            if (sub > MT_RHO_MAX_GRID) sub = MT_RHO_MAX_GRID;
            if (mt_cubature(rho_integrand, &c, 3, p0, p1, (double)j / NZ, (double)(j + 1) / NZ, sub,
                            sub, rel_tol, rel_tol * fmax(scale, 1e-6) / (NPHI * NZ),
                            225L * work * sub * sub, &r,
                            NULL) != MT_OK)
                return mt_rgb_black();
            for (k = 0; k < 3; ++k) sum[k] += r.value[k];
        }
    return mt_rgb_make((mt_real)sum[0], (mt_real)sum[1], (mt_real)sum[2]);
}

mt_rgb mt_bsdf_rho_quad(const mt_bsdf *b, mt_vec3 wo, unsigned flags, double rel_tol)
{
    mt_rgb r = mt_rgb_black();
    int i, n = mt_bsdf_count(b);
    mt_vec3 wl;
    if (!mt_v3_is_finite(wo) || mt_v3_is_zero(wo)) return r;
    wo = mt_v3_normalize(wo);
    wl = (mt_bsdf_mode(b) & MT_FIX_RHO_LOCAL) ? mt_bsdf_world_to_local(b, wo) : wo;
    for (i = 0; i < n; ++i) {
        const mt_bxdf *x = mt_bsdf_component(b, i);
        if (mt_type_matches(x->type, flags)) r = mt_rgb_add(r, mt_bxdf_rho_quad(x, wl, rel_tol));
    }
    return r;
}
