/*
 * pbrt-v2's perspective and orthographic cameras (ProjectiveCamera's
 * transforms, GenerateRayDifferential of each, the thin lens of both), as
 * released: with a lens, the differentials are the rays of the next pixels
 * through the same lens point (88cdb51; the 2012 snapshot gave the lens
 * camera the lensless camera's differentials).
 *
 * Erratum ortho-lens (MT_FIX_ORTHO_LENS): pbrt-v2's orthographic camera
 * puts the lens about the camera-space origin for every pixel, so with
 * lensradius > 0 it is a perspective projection from the origin that
 * matches the orthographic image only in the plane of focus, and its
 * differentials aim at depth focalDistance / d.z instead of the plane of
 * focus; corrected mode centres the lens on the pixel's point.
 */
#include "materia/sampling.h"
#include "tracer/camera.h"

void mt__camera_default_screen(mt_real frame, mt_real screen[4])
{
    if (frame > 1) {
        screen[0] = -frame;
        screen[1] = frame;
        screen[2] = -1;
        screen[3] = 1;
    } else {
        screen[0] = -1;
        screen[1] = 1;
        screen[2] = -1 / frame;
        screen[3] = 1 / frame;
    }
}

void mt__camera_init(mt__camera *c, int orthographic, mt_real fov_deg, const mt_real screen[4],
                     mt_real lens_radius, mt_real focal_distance, int xres, int yres,
                     const mt_transform *camera_to_world, mt_mode mode)
{
    /* ScreenToRaster = Scale(xres, yres, 1) * Scale(1 / (x1 - x0), 1 / (y0 - y1), 1)
     *                  * Translate(-x0, -y1, 0): screen y up, raster y down */
    mt_transform a = mt_scale((mt_real)xres, (mt_real)yres, 1);
    mt_transform b = mt_scale(1 / (screen[1] - screen[0]), 1 / (screen[2] - screen[3]), 1);
    mt_transform t = mt_translate(mt_v3(-screen[0], -screen[3], 0));
    mt_transform ab = mt_transform_compose(&a, &b);
    mt_transform s2r = mt_transform_compose(&ab, &t);
    mt_transform r2s = mt_transform_inverse(&s2r);
    mt_transform c2s = orthographic ? mt_orthographic(0, 1) : mt_perspective(fov_deg, (mt_real)1e-2, 1000);
    mt_transform s2c = mt_transform_inverse(&c2s);
    mt_vec3 o;
    int i, j;
    c->orthographic = orthographic;
    c->mode = mode;
    c->raster_to_camera = mt_transform_compose(&s2c, &r2s);
    c->camera_to_world = *camera_to_world;
    c->lens_radius = lens_radius;
    c->focal_distance = focal_distance;
    if (orthographic) {
        c->dx_camera = mt_transform_vector(&c->raster_to_camera, mt_v3(1, 0, 0));
        c->dy_camera = mt_transform_vector(&c->raster_to_camera, mt_v3(0, 1, 0));
    } else {
        o = mt_transform_point(&c->raster_to_camera, mt_v3(0, 0, 0));
        c->dx_camera = mt_v3_sub(mt_transform_point(&c->raster_to_camera, mt_v3(1, 0, 0)), o);
        c->dy_camera = mt_v3_sub(mt_transform_point(&c->raster_to_camera, mt_v3(0, 1, 0)), o);
    }
    /* raster depth 0 is the near plane (perspective) or z = 0 (orthographic):
     * there the projective map is affine in (x, y) */
    c->p00 = mt_transform_point(&c->raster_to_camera, mt_v3(0, 0, 0));
    for (i = 0; i < 3; ++i)
        for (j = 0; j < 4; ++j) c->c2w[i][j] = (mt_real)camera_to_world->m.m[i][j];
}

static inline mt_vec3 to_world_vector(const mt__camera *c, mt_vec3 v)
{
    return mt_v3(c->c2w[0][0] * v.x + c->c2w[0][1] * v.y + c->c2w[0][2] * v.z,
                 c->c2w[1][0] * v.x + c->c2w[1][1] * v.y + c->c2w[1][2] * v.z,
                 c->c2w[2][0] * v.x + c->c2w[2][1] * v.y + c->c2w[2][2] * v.z);
}

static inline mt_vec3 to_world_point(const mt__camera *c, mt_vec3 p)
{
    mt_vec3 v = to_world_vector(c, p);
    return mt_v3(v.x + c->c2w[0][3], v.y + c->c2w[1][3], v.z + c->c2w[2][3]);
}

/* The point on the lens of radius c->lens_radius for the sample. */
static mt_vec3 lens_point(const mt__camera *c, const mt__camera_sample *s)
{
    mt_real lu, lv;
    mt_concentric_sample_disk(s->lens_u, s->lens_v, &lu, &lv);
    return mt_v3(lu * c->lens_radius, lv * c->lens_radius, 0);
}

/* The thin lens of both cameras: the direction from the lens point to where
 * the ray (o, d) of the lensless camera meets the plane of focus
 * z = focalDistance (pbrt-v2 GenerateRay). */
static mt_vec3 through_focus(const mt__camera *c, mt_vec3 lens, mt_vec3 o, mt_vec3 d)
{
    mt_real ft = c->focal_distance / d.z;
    mt_vec3 focus = mt_v3_add(o, mt_v3_scale(d, ft));
    return mt_v3_normalize(mt_v3_sub(focus, lens));
}

void mt__camera_ray(const mt__camera *c, const mt__camera_sample *s, mt_raydiff *rd)
{
    mt_vec3 pc = mt_v3_add(c->p00, mt_v3_add(mt_v3_scale(c->dx_camera, s->image_x),
                                             mt_v3_scale(c->dy_camera, s->image_y)));
    mt_vec3 o, d, rxo, ryo, rxd, ryd;
    if (c->orthographic) {
        const mt_vec3 z = mt_v3(0, 0, 1);
        o = pc;
        d = z;
        rxo = mt_v3_add(o, c->dx_camera);
        ryo = mt_v3_add(o, c->dy_camera);
        rxd = ryd = d;
        if (c->lens_radius > 0) {
            mt_vec3 lens = lens_point(c, s);
            if (c->mode & MT_FIX_ORTHO_LENS) {
                /* corrected: the lens about the pixel's point, so that every
                 * pixel looks along +z through its own aperture; the ray of
                 * pixel x + 1 through the same lens point is this one moved
                 * by dxCamera */
                o = mt_v3_add(pc, lens);
                d = through_focus(c, o, pc, z);
                rxo = mt_v3_add(o, c->dx_camera);
                ryo = mt_v3_add(o, c->dy_camera);
                rxd = ryd = d;
            } else {
                /* pbrt-v2 OrthoCamera::GenerateRayDifferential (erratum
                 * ortho-lens): the lens about the camera-space origin
                 * whatever the pixel; the differentials (88cdb51) leave that
                 * lens point for Pcamera + dxCamera at the depth
                 * focalDistance / d.z of the main ray's direction d, not at
                 * the plane of focus */
                mt_real ft;
                o = lens;
                d = through_focus(c, o, pc, z);
                ft = c->focal_distance / d.z;
                rxo = ryo = o;
                rxd = mt_v3_normalize(mt_v3_sub(mt_v3_add(mt_v3_add(pc, c->dx_camera), mt_v3(0, 0, ft)), o));
                ryd = mt_v3_normalize(mt_v3_sub(mt_v3_add(mt_v3_add(pc, c->dy_camera), mt_v3(0, 0, ft)), o));
            }
        }
    } else {
        mt_vec3 pin = mt_v3_normalize(pc), pinx = mt_v3_normalize(mt_v3_add(pc, c->dx_camera)),
                piny = mt_v3_normalize(mt_v3_add(pc, c->dy_camera));
        if (c->lens_radius <= 0) {
            /* the pinhole: every ray leaves the camera's world position */
            mt_vec3 ow = mt_v3(c->c2w[0][3], c->c2w[1][3], c->c2w[2][3]);
            rd->ray = mt_ray_make(ow, to_world_vector(c, pin), 0, MT_RAY_TMAX);
            rd->has_differentials = 1;
            rd->rx_o = rd->ry_o = ow;
            rd->rx_d = to_world_vector(c, pinx);
            rd->ry_d = to_world_vector(c, piny);
            return;
        }
        /* pbrt-v2 PerspectiveCamera::GenerateRayDifferential with the
         * release's 88cdb51 (the 2012 snapshot gave the lens point the
         * pinhole's neighbour directions): the rays of the pixels x + 1
         * and y + 1 through the same lens point, aimed where the pinhole's
         * rays of those pixels meet the plane of focus */
        o = lens_point(c, s);
        d = through_focus(c, o, mt_v3(0, 0, 0), pin);
        rxo = ryo = o;
        rxd = through_focus(c, o, mt_v3(0, 0, 0), pinx);
        ryd = through_focus(c, o, mt_v3(0, 0, 0), piny);
    }
    rd->ray = mt_ray_make(to_world_point(c, o), to_world_vector(c, d), 0, MT_RAY_TMAX);
    rd->has_differentials = 1;
    rd->rx_o = to_world_point(c, rxo);
    rd->ry_o = to_world_point(c, ryo);
    rd->rx_d = to_world_vector(c, rxd);
    rd->ry_d = to_world_vector(c, ryd);
}
