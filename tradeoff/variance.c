/*
 * variance: the noise of one render, and what each dimension pair's
 * stratification buys (tradeoff/7-variance.sh; docs/BENCHMARKS.md, Noise per
 * sample).
 *
 *   variance [--mode pbrt-v2|corrected] [--seeds A B] [--threads N]
 *            SCENE.pbrt SPP CONFIG...
 *
 * For each CONFIG the scene is rendered twice, with seeds A and B (1 and 2),
 * and one line "LABEL rmse mean seconds" is printed: rmse is one render's
 * error, sqrt(mean over pixels and colour channels of (a - b)^2 / 2), which
 * needs no reference and no model of the samples (two renders with
 * different seeds are independent draws of the same estimator, so
 * E[(a - b)^2] = 2 Var); mean is the image mean, seconds the wall time of
 * both renders.
 *
 * A CONFIG is LABEL=ITEM,ITEM,... or LABEL= (the renderer as it is). Each
 * ITEM draws some values independently at random (a hash of the pixel, the
 * pair, the sample and the value) instead of from their low-discrepancy pair
 * (src/tracer/scene.h, mt_scene.independent):
 *   image          the image position
 *   all            every value
 *   vN[+][.PART]   path vertex (directlighting depth) N, or N and deeper
 *                  with "+", every pair or one PART of it:
 *     light        pair 0: the light choice and, reused, the light's sample
 *     lightcomp    pair 1's first value: the light's component (ShapeSet)
 *     rr           pair 1's second value: Russian roulette
 *     bsdf         pair 2: the next direction (component and direction),
 *                  which is also direct lighting's BSDF sample when the BSDF
 *                  has no specular component
 *     mis          pair 3: direct lighting's own BSDF sample (BSDFs with a
 *                  specular component; directlighting "one")
 *     specular     pairs 4, 5, 6: directlighting's specular directions
 *   own-choice     pbrt-v2's light choice: a value of its own (pair 5's first)
 *                  instead of the light sample's first value, rescaled
 *   chosen-bsdf    pbrt-v2's EstimateDirect: the BSDF sample of direct
 *                  lighting drawn for the chosen light only (pair 3, a ray of
 *                  its own, times the light count) instead of the path's
 *                  continuation counting for whichever light it finds
 *
 * Exit status 1 on a scene or render error, 2 on a wrong command line.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "materia/render.h"
#include "tracer/scene.h"

static int usage(void)
{
    fprintf(stderr, "usage: variance [--mode pbrt-v2|corrected] [--seeds A B] [--threads N] "
                    "SCENE.pbrt SPP LABEL=[ITEM,...] ...\n");
    return 2;
}

/* The bits of one vertex's entry that PART names; 0 for an unknown part. */
static unsigned part_bits(const char *part)
{
    if (!part || !*part) return 0xffffu;
    if (strcmp(part, "light") == 0) return 0x3u;
    if (strcmp(part, "lightcomp") == 0) return 0x4u;
    if (strcmp(part, "rr") == 0) return 0x8u;
    if (strcmp(part, "bsdf") == 0) return 0x30u;
    if (strcmp(part, "mis") == 0) return 0xc0u;
    if (strcmp(part, "specular") == 0) return 0x3f00u;
    return 0;
}

/* Sets the scene's independent values for one CONFIG; 0 on a bad item. */
static int apply(mt_scene *s, const char *spec)
{
    char buf[512], *item, *save = NULL;
    int v;
    memset(s->independent, 0, sizeof s->independent);
    s->independent_image = 0;
    s->measure_own_choice = s->measure_chosen_bsdf = 0;
    if (strlen(spec) >= sizeof buf) return 0;
    strcpy(buf, spec);
    for (item = strtok_r(buf, ",", &save); item; item = strtok_r(NULL, ",", &save)) {
        if (strcmp(item, "image") == 0) {
            s->independent_image = 1;
        } else if (strcmp(item, "own-choice") == 0) {
            s->measure_own_choice = 1;
        } else if (strcmp(item, "chosen-bsdf") == 0) {
            s->measure_chosen_bsdf = 1;
        } else if (strcmp(item, "all") == 0) {
            s->independent_image = 1;
            for (v = 0; v < MT__INDEPENDENT_VERTICES; ++v) s->independent[v] = 0xffffu;
        } else if (item[0] == 'v') {
            char *end, *dot = strchr(item, '.');
            long n = strtol(item + 1, &end, 10);
            int deeper = *end == '+';
            unsigned bits = part_bits(dot ? dot + 1 : NULL);
            if (end == item + 1 || n < 0 || n >= MT__INDEPENDENT_VERTICES || !bits) return 0;
            if (deeper) ++end;
            if (*end != '\0' && *end != '.') return 0;
            for (v = (int)n; v < (deeper ? MT__INDEPENDENT_VERTICES : (int)n + 1); ++v)
                s->independent[v] |= (uint16_t)bits;
        } else {
            return 0;
        }
    }
    return 1;
}

int main(int argc, char **argv)
{
    mt_render_options o;
    mt_error err;
    mt_scene *s;
    char buf[1024];
    uint64_t seeds[2] = {1, 2};
    int i = 1, spp, status = 0;
    mt_render_options_default(&o);
    o.warn = NULL;
    while (i < argc && argv[i][0] == '-' && argv[i][1] == '-') {
        if (strcmp(argv[i], "--mode") == 0 && i + 1 < argc) {
            if (strcmp(argv[i + 1], "corrected") == 0) o.mode = MT_MODE_CORRECTED;
            else if (strcmp(argv[i + 1], "pbrt-v2") != 0) return usage();
            i += 2;
        } else if (strcmp(argv[i], "--seeds") == 0 && i + 2 < argc) {
            seeds[0] = strtoull(argv[i + 1], NULL, 10);
            seeds[1] = strtoull(argv[i + 2], NULL, 10);
            i += 3;
        } else if (strcmp(argv[i], "--threads") == 0 && i + 1 < argc) {
            o.threads = atoi(argv[i + 1]);
            i += 2;
        } else {
            return usage();
        }
    }
    if (argc - i < 3 || (spp = atoi(argv[i + 1])) <= 0 || seeds[0] == seeds[1]) return usage();
    if (!(s = mt_scene_load(argv[i], &o, &err))) {
        fprintf(stderr, "variance: %s\n", mt_error_format(&err, buf, sizeof buf));
        return 1;
    }
    o.spp = spp;
    for (i += 2; i < argc && status == 0; ++i) {
        const char *eq = strchr(argv[i], '=');
        mt_image img[2];
        mt_render_stats st[2];
        double sq = 0, sum = 0;
        size_t n, k;
        int r;
        if (!eq || !apply(s, eq + 1)) {
            fprintf(stderr, "variance: bad configuration '%s'\n", argv[i]);
            status = 2;
            break;
        }
        for (r = 0; r < 2; ++r) {
            o.seed = seeds[r];
            if (mt_scene_render(s, &o, &img[r], NULL, &st[r], &err) != MT_OK) {
                fprintf(stderr, "variance: %s\n", mt_error_format(&err, buf, sizeof buf));
                if (r) mt_image_destroy(&img[0]);
                status = 1;
                break;
            }
        }
        if (status) break;
        n = (size_t)img[0].width * (size_t)img[0].height * (size_t)img[0].channels;
        for (k = 0; k < n; ++k) {
            double d = (double)img[0].data[k] - (double)img[1].data[k];
            sq += d * d;
            sum += (double)img[0].data[k] + (double)img[1].data[k];
        }
        printf("%.*s %.6g %.6g %.2f\n", (int)(eq - argv[i]), argv[i], sqrt(sq / (double)n / 2),
               sum / (double)n / 2, st[0].seconds + st[1].seconds);
        fflush(stdout);
        mt_image_destroy(&img[0]);
        mt_image_destroy(&img[1]);
    }
    mt_scene_destroy(s);
    return status;
}
