/*
 * Core types: the arena's pbrt-v2 semantics, PCG32, the Monte Carlo mappings,
 * errors, frames, transforms and the allocation hooks.
 */
#include <stdint.h>
#include <string.h>
#include "support/check.h"
#include "materia/transform.h"

static void test_arena(void)
{
    mt_arena *a = mt_arena_create(1024);
    int aligned = 1, i;
    size_t blocks;
    char *p, *q, *big;
    unsigned long before;
    for (i = 1; i < 200; ++i) {
        p = mt_arena_alloc(a, (size_t)i);
        if (((uintptr_t)p & 15) != 0) aligned = 0;
    }
    t_check(aligned, "arena: every allocation is 16-byte aligned", "misaligned pointer");
    blocks = mt_arena_blocks(a);
    t_check(blocks > 1, "arena: requests beyond a block take new blocks", "%zu blocks", blocks);
    /* pbrt-v2 FreeAll: blocks are kept and reused, so the same workload after
     * a reset allocates nothing from the heap. */
    mt_arena_reset(a);
    before = mt_alloc_count();
    for (i = 1; i < 200; ++i) mt_arena_alloc(a, (size_t)i);
    t_check(mt_alloc_count() == before && mt_arena_blocks(a) == blocks,
            "arena: reset reuses blocks without allocating", "%lu heap allocations after reset",
            mt_alloc_count() - before);
    /* A request larger than the block size gets a block of its own. */
    big = mt_arena_alloc(a, 5000);
    memset(big, 1, 5000);
    t_check(big != NULL && mt_arena_bytes(a) >= 5000, "arena: large request served", "NULL");
    /* Consecutive small allocations are adjacent, rounded up to 16 bytes. */
    mt_arena_reset(a);
    p = mt_arena_alloc(a, 1);
    q = mt_arena_alloc(a, 17);
    t_check(q - p == 16, "arena: sizes rounded up to 16 bytes", "distance %td", q - p);
    t_check(mt_arena_alloc(a, SIZE_MAX) == NULL, "arena: absurd request fails cleanly", "non-NULL");
    mt_arena_destroy(a);
    /* Fault injection: the creation's allocations fail cleanly. */
    for (i = 0; i < 2; ++i) {
        mt_alloc_fail_after(i);
        a = mt_arena_create(0);
        mt_alloc_fail_after(-1);
        t_check(a == NULL, "arena: creation reports allocation failure", "allocation %d ignored", i);
        mt_arena_destroy(a);
    }
}

static void test_rng(void)
{
    mt_rng r1, r2;
    int i, same = 1, inrange = 1;
    double sum = 0;
    uint32_t counts[10] = {0};
    mt_rng_seed(&r1, 42, 54);
    /* The PCG paper's reference output for pcg32 seeded (42, 54). */
    t_check(mt_rng_u32(&r1) == 0xa15c02b7u && mt_rng_u32(&r1) == 0x7b47f409u,
            "rng: PCG32 reference sequence", "differs from pcg32_random_r");
    mt_rng_seed(&r1, 7, 3);
    mt_rng_seed(&r2, 7, 3);
    for (i = 0; i < 1000; ++i)
        if (mt_rng_u32(&r1) != mt_rng_u32(&r2)) same = 0;
    t_check(same, "rng: same seed, same sequence", "sequences differ");
    for (i = 0; i < 100000; ++i) {
        mt_real u = mt_rng_uniform(&r1);
        if (!(u >= 0 && u < 1)) inrange = 0;
        sum += u;
        counts[mt_rng_bounded(&r1, 10)]++;
    }
    t_check(inrange, "rng: uniform in [0, 1)", "value outside");
    t_near(sum / 100000, 0.5, 4 * 0.2887 / sqrt(100000.0), "rng: uniform mean (4 sigma)");
    for (i = 0, same = 1; i < 10; ++i)
        if (fabs(counts[i] - 10000.0) > 5 * sqrt(9000.0)) same = 0;
    t_check(same, "rng: bounded is uniform (5 sigma per bin)", "a bin is off");
}

static void test_sampling(void)
{
    mt_real x, y;
    mt_vec3 w;
    int i, unit = 1;
    mt_rng r;
    double s = 0;
    mt_concentric_sample_disk(0.5f, 0.5f, &x, &y);
    t_check(x == 0 && y == 0, "sampling: concentric disk centre", "(%g, %g)", x, y);
    mt_concentric_sample_disk(1, 0.5f, &x, &y);
    t_near(x, 1, 1e-6, "sampling: concentric disk (1, .5) -> (1, 0) x");
    t_near(y, 0, 1e-6, "sampling: concentric disk (1, .5) -> (1, 0) y");
    /* Region 2 of Shirley-Chiu: (u1, u2) = (0.5, 1) -> (0, 1). */
    mt_concentric_sample_disk(0.5f, 1, &x, &y);
    t_near(x, 0, 1e-6, "sampling: concentric disk (.5, 1) -> (0, 1) x");
    t_near(y, 1, 1e-6, "sampling: concentric disk (.5, 1) -> (0, 1) y");
    mt_rng_seed(&r, 1, 1);
    for (i = 0; i < 20000; ++i) {
        mt_real u1 = mt_rng_uniform(&r), u2 = mt_rng_uniform(&r);
        w = mt_cosine_sample_hemisphere(u1, u2);
        if (fabs(mt_v3_len(w) - 1) > 1e-5 || w.z < 0) unit = 0;
        s += w.z; /* E[cos] under the cosine pdf is 2/3 */
        w = mt_uniform_sample_sphere(u1, u2);
        if (fabs(mt_v3_len(w) - 1) > 1e-5) unit = 0;
        w = mt_uniform_sample_cone(u1, u2, 0.5f);
        if (w.z < 0.5f - 1e-6 || fabs(mt_v3_len(w) - 1) > 1e-5) unit = 0;
    }
    t_check(unit, "sampling: hemisphere, sphere and cone samples are unit and in range", "no");
    t_near(s / 20000, 2.0 / 3.0, 4 * sqrt(1.0 / 18 / 20000), "sampling: cosine hemisphere E[cos] = 2/3");
    w = mt_uniform_sample_hemisphere(0.25f, 0.25f);
    t_near(w.z, 0.25, 1e-7, "sampling: uniform hemisphere z = u1");
    t_near(w.y, sqrt(1 - 0.0625), 1e-6, "sampling: uniform hemisphere phi = 2 pi u2");
    t_near(mt_spherical_theta(mt_v3(0, 0, -1)), MT_PI, 1e-6, "sampling: spherical theta");
    t_near(mt_spherical_phi(mt_v3(0, -1, 0)), 1.5 * MT_PI, 1e-6, "sampling: spherical phi in [0, 2pi)");
    t_near(mt_power_heuristic(1, 0, 1, 0), 0, 0, "sampling: power heuristic of two zero pdfs is 0");
}

static void test_error(void)
{
    mt_error e;
    char buf[256];
    mt_error_clear(&e);
    mt_error_param(&e, MT_ERR_INVALID, "roughness", "must be positive");
    mt_error_locate(&e, "scene.pbrt", 12, 7);
    mt_error_format(&e, buf, sizeof buf);
    t_check(!strcmp(buf, "scene.pbrt:12:7: parameter \"roughness\": must be positive"),
            "error: formatted with file, line, column and parameter", "got '%s'", buf);
    t_check(mt_error_set(NULL, MT_ERR_IO, "x") == MT_ERR_IO, "error: NULL err is allowed", "no");
}

static void test_frame_transform(void)
{
    mt_vec3 n = mt_v3_normalize(mt_v3(0.3f, -0.4f, 0.866f)), v = mt_v3(0.1f, 0.7f, -0.2f);
    mt_frame f = mt_frame_from_normal(n);
    mt_vec3 back = mt_frame_to_world(&f, mt_frame_to_local(&f, v));
    mt_transform t, ti, id;
    mt_vec3 p;
    mt_error err;
    double m[16] = {1, 2, 3, 4, 0, 1, 0, 0, 0, 0, 2, 0, 0, 0, 0, 0};
    t_near(mt_v3_dot(f.s, f.t) + mt_v3_dot(f.s, f.n) + mt_v3_dot(f.t, f.n), 0, 1e-6,
           "frame: orthogonal axes");
    t_near(mt_v3_len(mt_v3_sub(back, v)), 0, 1e-6, "frame: local/world round trip");
    t = mt_rotate(90, mt_v3(0, 0, 1));
    p = mt_transform_point(&t, mt_v3(1, 0, 0));
    t_near(p.y, 1, 1e-6, "transform: Rotate 90 about z maps x to y");
    t = mt_transform_compose(&t, &(mt_transform){mt_translate(mt_v3(1, 2, 3)).m,
                                                 mt_translate(mt_v3(1, 2, 3)).minv});
    ti = mt_transform_inverse(&t);
    id = mt_transform_compose(&t, &ti);
    p = mt_transform_point(&id, mt_v3(5, -6, 7));
    t_near(mt_v3_len(mt_v3_sub(p, mt_v3(5, -6, 7))), 0, 1e-5, "transform: T * T^-1 = I");
    t_check(mt_transform_swaps_handedness(&(mt_transform){mt_scale(-1, 1, 1).m, mt_scale(-1, 1, 1).minv}),
            "transform: Scale -1 1 1 swaps handedness", "no");
    t_check(mt_transform_from_matrix(m, &t, &err) == MT_ERR_INVALID,
            "transform: singular matrix rejected", "accepted");
}

int main(void)
{
    test_arena();
    test_rng();
    test_sampling();
    test_error();
    test_frame_transform();
    return t_status();
}
