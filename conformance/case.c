/*
 * A configuration of the suite (cf_case): its lines, its incoming
 * directions, and the seeds and random numbers its checks draw, so that a
 * check of one direction can be run again alone (--check, --wo, --repro)
 * and give the same samples.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "impl.h"

cf_v3 cf_v3_make(double x, double y, double z)
{
    cf_v3 v;
    v.x = x;
    v.y = y;
    v.z = z;
    return v;
}

/* Rounded through a volatile float: GCC 12's SLP vectorizer can drop the
 * conversions of (double)(float)x when two lanes are vectorized together
 * (docs/CONTRIBUTING.md). */
static double to_float(double x)
{
    volatile float f = (float)x;
    return f;
}

cf_v3 cf_v3_float(cf_v3 v) { return cf_v3_make(to_float(v.x), to_float(v.y), to_float(v.z)); }

int cf_case_add_line(cf_case *c, const char *line, const char *data)
{
    const char *p;
    size_t n = strlen(line) + 1, at = 0;
    char *s;
    if (c->nlines == CF_MAX_LINES) return -1;
    for (p = line; data && (p = strstr(p, "@DATA@")); p += 6) n += strlen(data);
    if (!(s = malloc(n))) return -1;
    for (p = line; *p;) {
        if (data && !strncmp(p, "@DATA@", 6)) {
            memcpy(s + at, data, strlen(data));
            at += strlen(data);
            p += 6;
        } else {
            s[at++] = *p++;
        }
    }
    s[at] = 0;
    c->lines[c->nlines++] = s;
    return 0;
}

int cf_case_set_data(cf_case *c, const char *data)
{
    int i, n = c->nlines;
    char *old[CF_MAX_LINES];
    memcpy(old, c->lines, sizeof old);
    c->nlines = 0;
    for (i = 0; i < n; ++i) {
        if (cf_case_add_line(c, old[i], data)) {
            /* keep what is left as it was: freed by cf_case_free */
            for (; i < n; ++i) c->lines[c->nlines++] = old[i];
            return -1;
        }
        free(old[i]);
    }
    return 0;
}

void cf_case_free(cf_case *c)
{
    int i;
    for (i = 0; i < c->nlines; ++i) free(c->lines[i]);
    c->nlines = 0;
}

/* The suite's incoming directions, per side: near-normal at several
 * azimuths (a sampler that loses precision there shows it only at some:
 * at 0 or 90 degrees one of x, y is exact), then 0.7, 0.3 and grazing. No
 * azimuth is a multiple of 45 degrees. --quick keeps the first near-normal
 * one, 0.7 and grazing. */
static const struct {
    double cos, phi; /* phi in radians */
    int quick;
} wo_set[] = {
    {0.9999, 0.7, 1},        /* 40.1 degrees */
    {1 - 1e-6, 1.9, 0},      /* 108.9 */
    {0.9999, 4.0, 0},        /* 229.2 */
    {0.7, 2.0, 1},
    {0.3, 3.3, 0},
    {0.03, 4.6, 1},
};

int cf_case_wo(const cf_case *c, int quick, cf_v3 *wo)
{
    int n = 0, side, k, sides = (c->flags & CF_CASE_TWO_SIDED) ? 2 : 1;
    if (c->nwo > 0) {
        for (k = 0; k < c->nwo; ++k) wo[k] = cf_v3_float(c->wo[k]);
        return c->nwo;
    }
    for (side = 0; side < sides; ++side)
        for (k = 0; k < (int)(sizeof wo_set / sizeof wo_set[0]); ++k) {
            double cz = wo_set[k].cos, s = sqrt(1 - cz * cz), phi = wo_set[k].phi;
            if (quick && !wo_set[k].quick) continue;
            wo[n++] = cf_v3_float(cf_v3_make(s * cos(phi), s * sin(phi), side ? -cz : cz));
        }
    return n;
}

static uint64_t run_seed;

void cf_set_run_seed(uint64_t seed) { run_seed = seed; }

uint64_t cf_seed(const char *name, int k)
{
    uint64_t s = 0x9e3779b97f4a7c15ULL * (uint64_t)(k + 1);
    for (; *name; ++name) s = s * 31 + (unsigned char)*name;
    if (run_seed) { /* a seeded run: every stream moved by a mix of the seed (splitmix64's finalizer) */
        uint64_t z = run_seed * 0x9e3779b97f4a7c15ULL;
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        s ^= z ^ (z >> 31);
    }
    return s;
}

/* The double build's uniform can round up to 1.0f (about one in 2^25; the
 * protocol rightly refuses u = 1), so it stops at the float below 1. The
 * float build's uniform is already such a float: the same numbers. */
/* the pilot's seeds: far from the indices of the other streams (directions
 * 0 to 15, pairs 99, probes 3 and 7) */
#define CF_PILOT_SEED 1000

float cf_u_float(mt_rng *rng)
{
    float u = (float)mt_rng_uniform(rng);
    return u < 1 ? u : 0x1.fffffep-1f;
}

void cf_sample_stream(mt_rng *rng, const char *name, int w, int pilot)
{
    /* the main samples are stream 77 of the direction's seed (as before the
     * pilot existed); the pilot has a seed of its own: two streams of PCG32
     * from one seed are not independent (their states differ by a sequence
     * of the same generator), and the cells laid by the pilot must be
     * independent of the samples counted in them */
    mt_rng_seed(rng, cf_seed(name, pilot ? CF_PILOT_SEED + w : w), 77);
}

void cf_sample_next(mt_rng *rng, int sample_numbers, long n, float (*u)[3])
{
    long i;
    for (i = 0; i < n; ++i) {
        u[i][0] = cf_u_float(rng);
        u[i][1] = cf_u_float(rng);
        u[i][2] = cf_u_float(rng);
        if (sample_numbers == 2) u[i][2] = 0.5f;
    }
}

void cf_sample_numbers(const char *name, int w, int pilot, int sample_numbers, long n, float (*u)[3])
{
    mt_rng rng;
    cf_sample_stream(&rng, name, w, pilot);
    cf_sample_next(&rng, sample_numbers, n, u);
}

int cf_case_from_config(cf_case *c, const cf_impl_config *k, const char *data)
{
    int j;
    memset(c, 0, sizeof *c);
    snprintf(c->name, sizeof c->name, "%s", k->name);
    for (j = 0; j < CI_MAX_LINES && k->lines[j]; ++j)
        if (cf_case_add_line(c, k->lines[j], data)) {
            cf_case_free(c);
            return -1;
        }
    c->flags = ((k->flags & CI_TWO_SIDED) ? CF_CASE_TWO_SIDED : 0) | ((k->flags & CI_SHADING_GAP) ? CF_CASE_SHADING_GAP : 0) |
               ((k->flags & CI_QUICK) ? CF_CASE_QUICK : 0);
    c->expect = (k->flags & CI_FURNACE_LE1) ? CF_EXPECT_LE : CF_EXPECT_NONE;
    c->expect_rho = 1;
    c->lobe_exponent = k->lobe_exponent;
    c->source = "builtin";
    return 0;
}
