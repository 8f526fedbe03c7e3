/*
 * The configurations --impl runs: pbrt-v2 statements (one per line, as an
 * implementation reads them) and shading-point lines, covering the 13
 * materials across their parameters and extremes: roughness 0.001 and 1,
 * index near 1 and 2.4, anisotropic substrate, mix amounts 0 and 1,
 * textured parameters, bump maps and a tilted geometric normal. "@DATA@"
 * stands for the data directory (absolute), where the suite writes the
 * files some configurations name (cf_impl_write_data).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "impl.h"
#include "materia/tools/merl.h"

#define LE1 CI_FURNACE_LE1
#define TWO CI_TWO_SIDED
#define GAP CI_SHADING_GAP
#define Q CI_QUICK
#define TILT "at ng 0.6 0 0.8"
#define CHECKS(name, a, b) \
    "Texture \"" name "\" \"float\" \"checkerboard\" \"float uscale\" [4] \"float vscale\" [4] \"float tex1\" [" a "] \"float tex2\" [" b "]"

static const cf_impl_config configs[] = {
    /* matte: Lambertian and Oren-Nayar */
    {"matte Kd=1", {"Material \"matte\" \"rgb Kd\" [1 1 1]"}, LE1 | Q, 0},
    {"matte default", {"Material \"matte\""}, LE1, 0},
    {"matte Kd=0.8 sigma=20", {"Material \"matte\" \"rgb Kd\" [.8 .8 .8] \"float sigma\" [20]"}, LE1 | Q, 0},
    {"matte Kd=0.9 sigma=90", {"Material \"matte\" \"rgb Kd\" [.9 .9 .9] \"float sigma\" [90]"}, LE1, 0},
    {"matte coloured Kd=0.7,0.2,0.05", {"Material \"matte\" \"rgb Kd\" [.7 .2 .05]"}, LE1, 0},
    {"matte textured Kd (checkerboard)",
     {"Texture \"c\" \"color\" \"checkerboard\" \"float uscale\" [4] \"float vscale\" [4] \"rgb tex1\" [.9 .1 .1] \"rgb tex2\" [.1 .1 .9]",
      "Material \"matte\" \"texture Kd\" \"c\"", "at uv 0.1 0.3"},
     LE1, 0},
    {"matte ng tilted 37 deg", {"Material \"matte\" \"rgb Kd\" [.8 .8 .8]", TILT}, LE1 | GAP | TWO, 0},
    /* a scaled solid texture: pbrt-v2's wrinkled reads only octaves and
     * roughness (textures/wrinkled.cpp), its mapping is the transform the
     * Texture statement is declared under (erratum mapping-3d: pbrt-v2
     * applies it as world to texture, corrected mode its inverse) */
    {"matte with a bump map", {"TransformBegin", "Scale .3 .3 .3",
      "Texture \"w\" \"float\" \"wrinkled\" \"integer octaves\" [5] \"float roughness\" [.4]", "TransformEnd",
      "Material \"matte\" \"texture bumpmap\" \"w\" \"rgb Kd\" [.9 .9 .9]", "at p 0.3 0.7 0.1"}, LE1 | GAP, 0},
    /* plastic: Lambertian + Blinn microfacet, dielectric Fresnel */
    {"plastic default", {"Material \"plastic\""}, LE1 | Q, 10},
    {"plastic roughness=0.001", {"Material \"plastic\" \"rgb Kd\" [.3 .3 .3] \"rgb Ks\" [.5 .5 .5] \"float roughness\" [.001]"}, LE1 | Q, 1000},
    {"plastic roughness=1", {"Material \"plastic\" \"rgb Kd\" [.3 .3 .3] \"rgb Ks\" [.5 .5 .5] \"float roughness\" [1]"}, LE1, 1},
    {"plastic Kd=1 Ks=1 r=0.3 (additive)", {"Material \"plastic\" \"rgb Kd\" [1 1 1] \"rgb Ks\" [1 1 1] \"float roughness\" [.3]"}, 0, 3.4},
    {"plastic textured roughness", {CHECKS("r", ".01", ".3"), "Material \"plastic\" \"texture roughness\" \"r\"", "at uv 0.3 0.3"}, LE1, 100},
    {"plastic ng tilted 37 deg", {"Material \"plastic\"", TILT}, LE1 | GAP | TWO, 10},
    {"plastic with a bump map (dots)", {"Texture \"d\" \"float\" \"dots\" \"float inside\" [0.05] \"float outside\" [0]",
      "Material \"plastic\" \"texture bumpmap\" \"d\"", "at uv 0.37 0.61 p 0.2 0.4 0"}, LE1 | GAP, 10},
    /* glass: specular reflection and transmission */
    {"glass default", {"Material \"glass\""}, LE1 | TWO | Q, 0},
    {"glass index=1.00001", {"Material \"glass\" \"float index\" [1.00001]"}, LE1 | TWO, 0},
    {"glass index=2.4 Kt=0.5", {"Material \"glass\" \"float index\" [2.4] \"rgb Kt\" [.5 .5 .5]"}, LE1 | TWO, 0},
    {"glass coloured Kr Kt", {"Material \"glass\" \"rgb Kr\" [.9 .5 .2] \"rgb Kt\" [.2 .6 .9] \"float index\" [1.33]"}, LE1 | TWO, 0},
    {"glass ng tilted 37 deg", {"Material \"glass\"", TILT}, TWO, 0},
    /* mirror */
    {"mirror default", {"Material \"mirror\""}, LE1 | Q, 0},
    {"mirror textured Kr", {"Texture \"k\" \"color\" \"checkerboard\" \"float uscale\" [4] \"float vscale\" [4] \"rgb tex1\" [.9 .9 .9] \"rgb tex2\" [.2 .5 .7]",
      "Material \"mirror\" \"texture Kr\" \"k\"", "at uv 0.6 0.1"}, LE1, 0},
    /* metal: Blinn with conductor Fresnel */
    {"metal default (copper)", {"Material \"metal\""}, LE1 | Q, 100},
    {"metal roughness=0.001", {"Material \"metal\" \"float roughness\" [.001]"}, LE1, 1000},
    {"metal roughness=1", {"Material \"metal\" \"float roughness\" [1]"}, LE1, 1},
    {"metal eta and k from spectrum files", {"Material \"metal\" \"spectrum eta\" \"@DATA@/eta.spd\" \"spectrum k\" \"@DATA@/k.spd\" \"float roughness\" [.1]"}, LE1, 10},
    /* shinymetal: additive (documented: albedo above 1) */
    {"shinymetal default (additive)", {"Material \"shinymetal\""}, 0, 10},
    {"shinymetal roughness=0.001", {"Material \"shinymetal\" \"rgb Ks\" [.3 .3 .3] \"rgb Kr\" [.3 .3 .3] \"float roughness\" [.001]"}, 0, 1000},
    /* substrate: FresnelBlend, isotropic and anisotropic */
    {"substrate default", {"Material \"substrate\""}, LE1 | Q, 10},
    {"substrate anisotropic u=0.001 v=0.5", {"Material \"substrate\" \"float uroughness\" [.001] \"float vroughness\" [.5]"}, LE1, 1000},
    {"substrate u=v=1", {"Material \"substrate\" \"float uroughness\" [1] \"float vroughness\" [1]"}, LE1, 1},
    {"substrate anisotropic u=0.05 v=0.2 coloured", {"Material \"substrate\" \"rgb Kd\" [.6 .3 .1] \"rgb Ks\" [.1 .2 .3] \"float uroughness\" [.05] \"float vroughness\" [.2]"}, LE1, 20},
    /* translucent: reflection and transmission lobes */
    {"translucent default", {"Material \"translucent\""}, LE1 | TWO | Q, 10},
    {"translucent Kd=Ks=0.5 r=t=1 (additive)", {"Material \"translucent\" \"rgb Kd\" [.5 .5 .5] \"rgb Ks\" [.5 .5 .5] \"rgb reflect\" [1 1 1] \"rgb transmit\" [1 1 1]"}, TWO, 10},
    {"translucent roughness=0.001 ng tilted", {"Material \"translucent\" \"float roughness\" [.001]", TILT}, TWO | GAP, 1000},
    /* uber */
    {"uber default", {"Material \"uber\""}, LE1, 10},
    {"uber opacity=0.5", {"Material \"uber\" \"rgb opacity\" [.5 .5 .5]"}, LE1 | TWO | Q, 10},
    {"uber Kr=Kt=0.5 (additive)", {"Material \"uber\" \"rgb Kr\" [.5 .5 .5] \"rgb Kt\" [.5 .5 .5]"}, TWO, 10},
    {"uber index=2.4 roughness=0.001", {"Material \"uber\" \"float index\" [2.4] \"float roughness\" [.001]"}, LE1, 1000},
    /* mix */
    {"mix matte/plastic amount=0.3",
     {"MakeNamedMaterial \"a\" \"string type\" \"matte\" \"rgb Kd\" [.8 .2 .2]",
      "MakeNamedMaterial \"b\" \"string type\" \"plastic\" \"rgb Kd\" [.1 .1 .5] \"rgb Ks\" [.5 .5 .5] \"float roughness\" [.1]",
      "Material \"mix\" \"string namedmaterial1\" \"a\" \"string namedmaterial2\" \"b\" \"rgb amount\" [.3 .3 .3]"},
     LE1 | Q, 10},
    {"mix amount=0", {"MakeNamedMaterial \"a\" \"string type\" \"matte\"", "MakeNamedMaterial \"b\" \"string type\" \"metal\"",
      "Material \"mix\" \"string namedmaterial1\" \"a\" \"string namedmaterial2\" \"b\" \"rgb amount\" [0 0 0]"}, LE1, 100},
    {"mix amount=1", {"MakeNamedMaterial \"a\" \"string type\" \"matte\"", "MakeNamedMaterial \"b\" \"string type\" \"metal\"",
      "Material \"mix\" \"string namedmaterial1\" \"a\" \"string namedmaterial2\" \"b\" \"rgb amount\" [1 1 1]"}, LE1, 100},
    {"mix glass/mirror amount=0.5", {"MakeNamedMaterial \"g\" \"string type\" \"glass\"", "MakeNamedMaterial \"m\" \"string type\" \"mirror\"",
      "Material \"mix\" \"string namedmaterial1\" \"g\" \"string namedmaterial2\" \"m\""}, LE1 | TWO, 0},
    {"mix textured amount", {"Texture \"t\" \"color\" \"checkerboard\" \"float uscale\" [4] \"float vscale\" [4] \"rgb tex1\" [.2 .2 .2] \"rgb tex2\" [.9 .5 .1]", "MakeNamedMaterial \"a\" \"string type\" \"substrate\"",
      "MakeNamedMaterial \"b\" \"string type\" \"matte\" \"rgb Kd\" [.2 .7 .2]",
      "Material \"mix\" \"string namedmaterial1\" \"a\" \"string namedmaterial2\" \"b\" \"texture amount\" \"t\"", "at uv 0.2 0.1"}, LE1, 10},
    /* measured: a MERL table written by the suite */
    {"measured MERL table (plastic)", {"Material \"measured\" \"string filename\" \"@DATA@/plastic.merl\""}, 0, 10},
    /* subsurface materials: their BSDF is a specular interface */
    {"subsurface default", {"Material \"subsurface\""}, LE1, 0},
    {"subsurface Ketchup index=1.5", {"Material \"subsurface\" \"string name\" \"Ketchup\" \"float index\" [1.5]"}, LE1, 0},
    {"kdsubsurface default", {"Material \"kdsubsurface\""}, LE1 | Q, 0},
    {"kdsubsurface textured Kd", {"Texture \"k\" \"color\" \"checkerboard\" \"float uscale\" [4] \"float vscale\" [4] \"rgb tex1\" [.9 .5 .2] \"rgb tex2\" [.2 .2 .2]",
      "Material \"kdsubsurface\" \"texture Kd\" \"k\" \"rgb Kr\" [.7 .7 .7]", "at uv 0.4 0.9"}, LE1, 0},
};

const cf_impl_config *cf_impl_configs(int *count)
{
    *count = (int)(sizeof configs / sizeof configs[0]);
    return configs;
}

/* Spectra of a made-up conductor (smooth, in pbrt-v2's .spd format:
 * wavelength in nm and value per line), and the MERL table of a plastic. */
int cf_impl_write_data(const char *dir, char *msg, size_t n)
{
    static const char *const names[2] = {"eta.spd", "k.spd"};
    char path[4096], tmp[4200];
    int f, i;
    mt_error err;
    mt_merl_options opt;
    for (f = 0; f < 2; ++f) {
        FILE *fp;
        snprintf(path, sizeof path, "%s/%s", dir, names[f]);
        snprintf(tmp, sizeof tmp, "%s.tmp", path);
        if (!(fp = fopen(tmp, "w"))) {
            snprintf(msg, n, "%s: cannot write", tmp);
            return -1;
        }
        for (i = 0; i <= 40; ++i) {
            double l = 380 + 10 * i, t = (l - 380) / 400;
            fprintf(fp, "%g %g\n", l, f ? 2.5 + 2 * t : 1.2 - 0.9 * t * (2 - t));
        }
        if (fclose(fp) || rename(tmp, path)) {
            snprintf(msg, n, "%s: cannot write", path);
            return -1;
        }
    }
    snprintf(path, sizeof path, "%s/plastic.merl", dir);
    memset(&opt, 0, sizeof opt);
    opt.at = MT_MERL_AT_CENTRE;
    mt_error_clear(&err);
    if (mt_merl_write_statements("Material \"plastic\" \"rgb Kd\" [.4 .2 .1] \"rgb Ks\" [.3 .3 .3] \"float roughness\" [.1]",
                                 &opt, path, &err)) {
        mt_error_format(&err, msg, n);
        return -1;
    }
    return 0;
}
