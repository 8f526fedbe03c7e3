/*
 * Transforms (pbrt-v2 transform.cpp): every transform carries its inverse,
 * built alongside it where the inverse is known in closed form and by
 * Gauss-Jordan elimination with full pivoting otherwise.
 */
#include <string.h>
#include "materia/transform.h"

static mt_matrix4 mat_identity(void)
{
    mt_matrix4 r;
    int i, j;
    for (i = 0; i < 4; ++i)
        for (j = 0; j < 4; ++j) r.m[i][j] = i == j;
    return r;
}

static mt_matrix4 mat_mul(const mt_matrix4 *a, const mt_matrix4 *b)
{
    mt_matrix4 r;
    int i, j;
    for (i = 0; i < 4; ++i)
        for (j = 0; j < 4; ++j)
            r.m[i][j] = a->m[i][0] * b->m[0][j] + a->m[i][1] * b->m[1][j] +
                        a->m[i][2] * b->m[2][j] + a->m[i][3] * b->m[3][j];
    return r;
}

static mt_matrix4 mat_transpose(const mt_matrix4 *a)
{
    mt_matrix4 r;
    int i, j;
    for (i = 0; i < 4; ++i)
        for (j = 0; j < 4; ++j) r.m[i][j] = a->m[j][i];
    return r;
}

/* Gauss-Jordan with full pivoting (pbrt-v2 Inverse). Returns 0 if singular. */
static int mat_inverse(const mt_matrix4 *a, mt_matrix4 *out)
{
    int indxc[4], indxr[4], ipiv[4] = {0, 0, 0, 0};
    double minv[4][4];
    int i, j, k, l, ll;
    memcpy(minv, a->m, sizeof minv);
    for (i = 0; i < 4; i++) {
        int irow = -1, icol = -1;
        double big = 0, pivinv;
        for (j = 0; j < 4; j++) {
            if (ipiv[j] == 1) continue;
            for (k = 0; k < 4; k++) {
                if (ipiv[k] == 0) {
                    if (fabs(minv[j][k]) >= big) {
                        big = fabs(minv[j][k]);
                        irow = j;
                        icol = k;
                    }
                } else if (ipiv[k] > 1) {
                    return 0;
                }
            }
        }
        if (irow < 0) return 0;
        ++ipiv[icol];
        if (irow != icol)
            for (k = 0; k < 4; ++k) {
                double t = minv[irow][k];
                minv[irow][k] = minv[icol][k];
                minv[icol][k] = t;
            }
        indxr[i] = irow;
        indxc[i] = icol;
        if (minv[icol][icol] == 0) return 0;
        pivinv = 1 / minv[icol][icol];
        minv[icol][icol] = 1;
        for (j = 0; j < 4; j++) minv[icol][j] *= pivinv;
        for (j = 0; j < 4; j++) {
            if (j != icol) {
                double save = minv[j][icol];
                minv[j][icol] = 0;
                for (k = 0; k < 4; k++) minv[j][k] -= minv[icol][k] * save;
            }
        }
    }
    for (l = 3; l >= 0; l--) {
        if (indxr[l] != indxc[l])
            for (ll = 0; ll < 4; ll++) {
                double t = minv[ll][indxr[l]];
                minv[ll][indxr[l]] = minv[ll][indxc[l]];
                minv[ll][indxc[l]] = t;
            }
    }
    for (i = 0; i < 4; ++i)
        for (j = 0; j < 4; ++j)
            if (!isfinite(minv[i][j])) return 0;
    memcpy(out->m, minv, sizeof minv);
    return 1;
}

static mt_transform make(const mt_matrix4 *m, const mt_matrix4 *minv)
{
    mt_transform t;
    t.m = *m;
    t.minv = *minv;
    return t;
}

mt_transform mt_transform_identity(void)
{
    mt_matrix4 i = mat_identity();
    return make(&i, &i);
}

mt_status mt_transform_from_matrix(const double m[16], mt_transform *out, mt_error *err)
{
    mt_matrix4 a, inv;
    int i;
    mt_error_clear(err);
    for (i = 0; i < 16; ++i) {
        if (!isfinite(m[i]))
            return mt_error_set(err, MT_ERR_INVALID, "transform matrix has a non-finite entry");
        a.m[i / 4][i % 4] = m[i];
    }
    if (!mat_inverse(&a, &inv))
        return mt_error_set(err, MT_ERR_INVALID, "transform matrix is singular");
    *out = make(&a, &inv);
    return MT_OK;
}

mt_transform mt_transform_inverse(const mt_transform *t) { return make(&t->minv, &t->m); }

mt_transform mt_transform_compose(const mt_transform *a, const mt_transform *b)
{
    mt_matrix4 m = mat_mul(&a->m, &b->m), minv = mat_mul(&b->minv, &a->minv);
    return make(&m, &minv);
}

int mt_transform_is_identity(const mt_transform *t)
{
    int i, j;
    for (i = 0; i < 4; ++i)
        for (j = 0; j < 4; ++j)
            if (t->m.m[i][j] != (i == j)) return 0;
    return 1;
}

int mt_transform_swaps_handedness(const mt_transform *t)
{
    const double(*m)[4] = t->m.m;
    double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                 m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                 m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    return det < 0;
}

mt_transform mt_translate(mt_vec3 d)
{
    mt_matrix4 m = mat_identity(), minv = mat_identity();
    m.m[0][3] = d.x;
    m.m[1][3] = d.y;
    m.m[2][3] = d.z;
    minv.m[0][3] = -(double)d.x;
    minv.m[1][3] = -(double)d.y;
    minv.m[2][3] = -(double)d.z;
    return make(&m, &minv);
}

mt_transform mt_scale(mt_real x, mt_real y, mt_real z)
{
    mt_matrix4 m = mat_identity(), minv = mat_identity();
    m.m[0][0] = x;
    m.m[1][1] = y;
    m.m[2][2] = z;
    minv.m[0][0] = 1.0 / x;
    minv.m[1][1] = 1.0 / y;
    minv.m[2][2] = 1.0 / z;
    return make(&m, &minv);
}

mt_transform mt_rotate(mt_real angle_deg, mt_vec3 axis)
{
    double len = sqrt((double)axis.x * axis.x + (double)axis.y * axis.y + (double)axis.z * axis.z);
    double ax = axis.x / len, ay = axis.y / len, az = axis.z / len;
    double theta = angle_deg * (3.14159265358979323846 / 180.0);
    double s = sin(theta), c = cos(theta);
    mt_matrix4 m = mat_identity(), mt;
    m.m[0][0] = ax * ax + (1 - ax * ax) * c;
    m.m[0][1] = ax * ay * (1 - c) - az * s;
    m.m[0][2] = ax * az * (1 - c) + ay * s;
    m.m[1][0] = ax * ay * (1 - c) + az * s;
    m.m[1][1] = ay * ay + (1 - ay * ay) * c;
    m.m[1][2] = ay * az * (1 - c) - ax * s;
    m.m[2][0] = ax * az * (1 - c) - ay * s;
    m.m[2][1] = ay * az * (1 - c) + ax * s;
    m.m[2][2] = az * az + (1 - az * az) * c;
    mt = mat_transpose(&m); /* a rotation's inverse is its transpose */
    return make(&m, &mt);
}

mt_status mt_look_at(mt_vec3 pos, mt_vec3 look, mt_vec3 up, mt_transform *out, mt_error *err)
{
    double dir[3] = {(double)look.x - pos.x, (double)look.y - pos.y, (double)look.z - pos.z};
    double u[3] = {up.x, up.y, up.z}, left[3], nu[3], l;
    mt_matrix4 cam2world = mat_identity(), world2cam;
    int i;
    mt_error_clear(err);
    l = sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    if (!(l > 0)) return mt_error_set(err, MT_ERR_INVALID, "LookAt: eye and target coincide");
    for (i = 0; i < 3; ++i) dir[i] /= l;
    l = sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    if (!(l > 0)) return mt_error_set(err, MT_ERR_INVALID, "LookAt: the up vector is zero");
    for (i = 0; i < 3; ++i) u[i] /= l;
    /* left = normalize(cross(up, dir)), newUp = cross(dir, left) */
    left[0] = u[1] * dir[2] - u[2] * dir[1];
    left[1] = u[2] * dir[0] - u[0] * dir[2];
    left[2] = u[0] * dir[1] - u[1] * dir[0];
    l = sqrt(left[0] * left[0] + left[1] * left[1] + left[2] * left[2]);
    if (!(l > 1e-12))
        return mt_error_set(err, MT_ERR_INVALID,
                            "LookAt: the up vector is parallel to the viewing direction");
    for (i = 0; i < 3; ++i) left[i] /= l;
    nu[0] = dir[1] * left[2] - dir[2] * left[1];
    nu[1] = dir[2] * left[0] - dir[0] * left[2];
    nu[2] = dir[0] * left[1] - dir[1] * left[0];
    for (i = 0; i < 3; ++i) {
        cam2world.m[i][0] = left[i];
        cam2world.m[i][1] = nu[i];
        cam2world.m[i][2] = dir[i];
    }
    cam2world.m[0][3] = pos.x;
    cam2world.m[1][3] = pos.y;
    cam2world.m[2][3] = pos.z;
    if (!mat_inverse(&cam2world, &world2cam))
        return mt_error_set(err, MT_ERR_INVALID, "LookAt: degenerate camera frame");
    *out = make(&world2cam, &cam2world);
    return MT_OK;
}

mt_transform mt_perspective(mt_real fov_deg, mt_real n, mt_real f)
{
    /* pbrt-v2: Scale(invTanAng, invTanAng, 1) * persp, with persp mapping
     * z in [n, f] to [0, 1] after the divide by z. */
    mt_matrix4 persp = mat_identity(), inv;
    mt_transform p, s;
    double invtan = 1.0 / tan((double)fov_deg * (3.14159265358979323846 / 180.0) / 2);
    persp.m[2][2] = f / (f - (double)n);
    persp.m[2][3] = -(double)f * n / (f - (double)n);
    persp.m[3][2] = 1;
    persp.m[3][3] = 0;
    mat_inverse(&persp, &inv);
    p = make(&persp, &inv);
    s = mt_scale((mt_real)invtan, (mt_real)invtan, 1);
    s.m.m[0][0] = s.m.m[1][1] = invtan;
    s.minv.m[0][0] = s.minv.m[1][1] = 1 / invtan;
    return mt_transform_compose(&s, &p);
}

mt_transform mt_orthographic(mt_real znear, mt_real zfar)
{
    mt_transform s = mt_scale(1, 1, 1 / (zfar - znear)), t = mt_translate(mt_v3(0, 0, -znear));
    return mt_transform_compose(&s, &t);
}

mt_vec3 mt_transform_point(const mt_transform *t, mt_vec3 p)
{
    const double(*m)[4] = t->m.m;
    double x = p.x, y = p.y, z = p.z;
    double xp = m[0][0] * x + m[0][1] * y + m[0][2] * z + m[0][3];
    double yp = m[1][0] * x + m[1][1] * y + m[1][2] * z + m[1][3];
    double zp = m[2][0] * x + m[2][1] * y + m[2][2] * z + m[2][3];
    double wp = m[3][0] * x + m[3][1] * y + m[3][2] * z + m[3][3];
    if (wp == 1) return mt_v3((mt_real)xp, (mt_real)yp, (mt_real)zp);
    return mt_v3((mt_real)(xp / wp), (mt_real)(yp / wp), (mt_real)(zp / wp));
}

mt_vec3 mt_transform_vector(const mt_transform *t, mt_vec3 v)
{
    const double(*m)[4] = t->m.m;
    double x = v.x, y = v.y, z = v.z;
    return mt_v3((mt_real)(m[0][0] * x + m[0][1] * y + m[0][2] * z),
                 (mt_real)(m[1][0] * x + m[1][1] * y + m[1][2] * z),
                 (mt_real)(m[2][0] * x + m[2][1] * y + m[2][2] * z));
}

mt_vec3 mt_transform_normal(const mt_transform *t, mt_vec3 n)
{
    const double(*mi)[4] = t->minv.m;
    double x = n.x, y = n.y, z = n.z;
    return mt_v3((mt_real)(mi[0][0] * x + mi[1][0] * y + mi[2][0] * z),
                 (mt_real)(mi[0][1] * x + mi[1][1] * y + mi[2][1] * z),
                 (mt_real)(mi[0][2] * x + mi[1][2] * y + mi[2][2] * z));
}
