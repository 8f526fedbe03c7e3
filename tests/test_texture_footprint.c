/*
 * Noise textures at wide footprints and under transforms, where the
 * reference values (whose footprints are all narrow) are silent. pbrt-v2's
 * octave count -1 - log2(s2)/2 is clamped to [0, maxOctaves]: renders by
 * pbrt-v2 itself (../shared/baselines/pbrt-v2/pbrt, an orthographic camera
 * over a matte plane whose Kd is mix(0.5, 1) by the texture, one distant
 * light of radiance pi straight above, directlighting, 8x8 pixels of 2.8
 * units at 16 spp: ray differentials of 0.7) gave every pixel exactly 0.5 for
 * fbm and windy (the texture exactly 0) and 0.58 for wrinkled scaled by 0.1
 * (Turbulence exactly 0.2 x 8 octaves). Unclamped, -0.49 octaves would fade
 * in half an octave of noise. Through the query protocol, in both modes.
 */
#include <math.h>
#include <stdio.h>
#include "materia.h"
#include "materia/tools/query.h"
#include "support/check.h"
#include "support/tquery.h"

static mt_query *q;

static int tex(const char *name, double *v, int n)
{
    char line[64];
    snprintf(line, sizeof line, "texture \"%s\"", name);
    return t_query_ask(q, line, v, n);
}

static int set(const char *line) { return t_query_ask(q, line, NULL, 0); }

static void wide_footprints(const char *mode)
{
    double v[3], w[3];
    char name[128];
    static const char *pts[] = {"at p 0.3 0.7 0.1", "at p -2.25 0.4 1.6", "at p 5.1 -3.3 0.77"};
    int i;
    if (!set("Texture \"f\" \"float\" \"fbm\"") || !set("Texture \"w\" \"float\" \"wrinkled\"") ||
        !set("Texture \"y\" \"float\" \"windy\"") ||
        !set("Texture \"w3\" \"float\" \"wrinkled\" \"integer octaves\" [3] \"float roughness\" [0.8]"))
        return;
    for (i = 0; i < 3; i++) {
        if (!set(pts[i]) || !set("at dpdx 0.7 0 0") || !set("at dpdy 0 0.1 0")) return;
        snprintf(name, sizeof name, "footprint %s: fbm exactly 0 at a footprint of 0.7 (point %d)", mode, i);
        if (tex("f", v, 1)) t_check(v[0] == 0, name, "%.9g", v[0]);
        snprintf(name, sizeof name, "footprint %s: wrinkled exactly 0.2 x 8 at 0.7 (point %d)", mode, i);
        if (tex("w", v, 1)) t_check(fabs(v[0] - (double)((mt_real)8 * (mt_real)0.2)) <= 1e-7, name, "%.9g", v[0]);
        snprintf(name, sizeof name, "footprint %s: wrinkled 3 octaves exactly 0.2 x 3 at 0.7 (point %d)", mode, i);
        if (tex("w3", v, 1)) t_check(fabs(v[0] - (double)((mt_real)3 * (mt_real)0.2)) <= 1e-7, name, "%.9g", v[0]);
        /* windy's wave height FBm(P) has no octave; its wind strength at a
         * tenth of the footprint has 2.8 */
        snprintf(name, sizeof name, "footprint %s: windy exactly 0 at 0.7 (point %d)", mode, i);
        if (tex("y", v, 1)) t_check(v[0] == 0, name, "%.9g", v[0]);
        /* just inside: 0.29 octaves, still no noise (SmoothStep(.3, .7, .3)) */
        if (!set("at dpdx 0.41 0 0")) return;
        snprintf(name, sizeof name, "footprint %s: fbm 0 at 0.29 octaves (point %d)", mode, i);
        if (tex("f", v, 1)) t_check(v[0] == 0, name, "%.9g", v[0]);
        if (!set("at dpdx 0.2 0 0")) return;
        snprintf(name, sizeof name, "footprint %s: fbm not 0 at 1.3 octaves (point %d)", mode, i);
        if (tex("f", v, 1)) t_check(v[0] != 0, name, "%.9g", v[0]);
    }
    /* marble's FBm sees P and the footprint times scale: at a footprint of
     * 0.2 and scale 3 it has no octave, so the variation has no effect */
    if (!set("at p 0.3 0.7 0.1") || !set("at dpdx 0.2 0 0") ||
        !set("Texture \"m\" \"color\" \"marble\" \"integer octaves\" [6] \"float roughness\" [0.7] "
             "\"float scale\" [3] \"float variation\" [0.3]") ||
        !set("Texture \"m0\" \"color\" \"marble\" \"float scale\" [3] \"float variation\" [0]"))
        return;
    snprintf(name, sizeof name, "footprint %s: marble scale 3 at 0.2: no FBm octave (variation moot)", mode);
    if (tex("m", v, 3) && tex("m0", w, 3))
        t_check(v[0] == w[0] && v[1] == w[1] && v[2] == w[2], name, "(%.9g %.9g %.9g) vs (%.9g %.9g %.9g)", v[0],
                v[1], v[2], w[0], w[1], w[2]);
    if (!set("at dpdx 0.02 0 0")) return;
    snprintf(name, sizeof name, "footprint %s: marble scale 3 at 0.02: FBm varies it", mode);
    if (tex("m", v, 3) && tex("m0", w, 3)) t_check(v[0] != w[0], name, "%.9g vs %.9g", v[0], w[0]);
    set("at dpdx 0 0 0");
    set("at dpdy 0 0 0");
}

/* A color fbm declared under Scale 3 3 3: pbrt-v2 maps world points and
 * footprints by the scale itself (erratum mapping-3d), three times wider, so
 * a footprint of 0.2 has no octave; corrected mode divides by 3 (2.9
 * octaves). */
static void under_scale(int corrected)
{
    double v[3];
    char name[128];
    if (!set(corrected ? "mode corrected" : "mode pbrt-v2") || !set("TransformBegin") || !set("Scale 3 3 3") ||
        !set("Texture \"c\" \"color\" \"fbm\"") || !set("TransformEnd") || !set("at p 0.3 0.7 0.1") ||
        !set("at dpdx 0.2 0 0"))
        return;
    snprintf(name, sizeof name, "footprint %s: color fbm under Scale 3 3 3 at 0.2",
             corrected ? "corrected" : "pbrt-v2");
    if (tex("c", v, 3)) {
        if (corrected)
            t_check(v[0] != 0 && v[0] == v[1] && v[1] == v[2], name, "%.9g %.9g %.9g: want a grey, not 0", v[0], v[1],
                    v[2]);
        else
            t_check(v[0] == 0 && v[1] == 0 && v[2] == 0, name, "%.9g %.9g %.9g: want exactly 0", v[0], v[1], v[2]);
    }
    set("at dpdx 0 0 0");
}

int main(void)
{
    mt_error err;
    q = mt_query_create(NULL, &err);
    if (!q) {
        t_fail("footprint: session", "%s", err.message);
        return t_status();
    }
    wide_footprints("pbrt-v2");
    under_scale(0);
    under_scale(1);
    wide_footprints("corrected"); /* the textures declared again in corrected mode */
    mt_query_destroy(q);
    return t_status();
}
