/*
 * Internal: pbrt-v2's projective cameras (core/camera.cpp ProjectiveCamera,
 * cameras/perspective.cpp, cameras/orthographic.cpp): raster to screen to
 * camera space, an optional thin lens, rays with differentials, camera to
 * world. Raster coordinates run over the whole film (x right, y down), in
 * pixels; the screen window maps onto it.
 */
#ifndef MT_TRACER_CAMERA_H
#define MT_TRACER_CAMERA_H

#include "tracer/geometry.h"

typedef struct mt__camera {
    int orthographic;
    mt_mode mode;                 /* MT_FIX_ORTHO_LENS is the camera's */
    mt_transform raster_to_camera;
    mt_transform camera_to_world;
    mt_real lens_radius, focal_distance;
    mt_vec3 dx_camera, dy_camera; /* one raster pixel in x and y, in camera space */
    mt_vec3 p00;                  /* raster (0, 0) in camera space: raster points of depth 0
                                     map affinely, p00 + x dx_camera + y dy_camera */
    mt_real c2w[3][4];            /* camera_to_world rounded to mt_real */
} mt__camera;

typedef struct mt__camera_sample {
    mt_real image_x, image_y; /* raster position */
    mt_real lens_u, lens_v;   /* [0, 1)^2 */
} mt__camera_sample;

/* screen = {xmin, xmax, ymin, ymax} (pbrt-v2's screenWindow), the film's full
 * resolution, fov in degrees (perspective only); mode: the scene's (erratum
 * ortho-lens). */
void mt__camera_init(mt__camera *c, int orthographic, mt_real fov_deg, const mt_real screen[4],
                     mt_real lens_radius, mt_real focal_distance, int xres, int yres,
                     const mt_transform *camera_to_world, mt_mode mode);

/* pbrt-v2's default screen window for a frame aspect ratio: [-frame, frame]
 * x [-1, 1] when frame > 1, else [-1, 1] x [-1/frame, 1/frame]; so fov spans
 * the shorter image axis. */
void mt__camera_default_screen(mt_real frame, mt_real screen[4]);

/* GenerateRayDifferential: the ray in world space, with differentials (with
 * a lens, the neighbour pixels' rays through the same lens point; the
 * orthographic camera's lens as the mode says). */
void mt__camera_ray(const mt__camera *c, const mt__camera_sample *s, mt_raydiff *rd);

#endif
