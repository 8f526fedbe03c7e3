/*
 * The BVH benchmarks' ray sets (bench/bvh.c, bench/embree/bvh_embree.c), so
 * that materia's BVH and Embree trace the very same rays:
 *   primary    pinhole rays through the pixel centres of a 1024x768 image,
 *              closest hit; the camera of real-bunny-measured.pbrt (LookAt
 *              0 .2 .2  -.02 .1 0  0 1 0, fov 60 on the shorter axis) for the
 *              bunny, otherwise one looking at the bounds' centre from 1.5
 *              diagonals away along (1, .3, .4), up +z, fov 40
 *   incoherent 1M rays, origins uniform in the bounds, directions uniform on
 *              the sphere (PCG32 seed 2024): closest hit
 *   occlusion  1M segments between two points uniform in the bounds (tmax 1):
 *              any hit
 */
#ifndef MT_TEST_TRAYSETS_H
#define MT_TEST_TRAYSETS_H

#include <stddef.h>
#include "tracer/geometry.h"

enum { T_RAYS_PRIMARY, T_RAYS_INCOHERENT, T_RAYS_OCCLUSION, T_RAY_SETS };
extern const char *const t_ray_set_names[T_RAY_SETS];

/* Allocates (malloc) and fills the three sets over the committed g's bounds;
 * bunny_camera picks the primary camera. Returns 0 when out of memory (then
 * nothing is left allocated). */
int t_ray_sets(const mt_geometry *g, int bunny_camera, mt_ray *sets[T_RAY_SETS],
               size_t counts[T_RAY_SETS]);
void t_ray_sets_free(mt_ray *sets[T_RAY_SETS]);

#endif
