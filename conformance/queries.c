/* Queries both builds answer alike, and ULP distances (queries.h). */
#include <float.h>
#include <math.h>
#include "queries.h"

mt_real cf_as_float(double x)
{
    volatile float f = (float)x;
    return f;
}

mt_vec3 cf_query_dir(mt_rng *r)
{
    double z = 1 - 2 * mt_rng_uniform_d(r), phi = 6.283185307179586 * mt_rng_uniform_d(r), s = sqrt(1 - z * z);
    return mt_v3(cf_as_float(s * cos(phi)), cf_as_float(s * sin(phi)), cf_as_float(z));
}

cf_query cf_query_next(mt_rng *r)
{
    /* one statement each: the order of evaluation of an initializer list's
     * calls is unspecified, the queries' must not be */
    cf_query q;
    q.wo = cf_query_dir(r);
    q.wi = cf_query_dir(r);
    q.uc = cf_as_float(mt_rng_uniform_d(r));
    q.u1 = cf_as_float(mt_rng_uniform_d(r));
    q.u2 = cf_as_float(mt_rng_uniform_d(r));
    return q;
}

double cf_ulp_distance(double a, double b, double floor, int bits)
{
    double m = fmax(fmax(fabs(a), fabs(b)), floor);
    int e;
    if (a == b || !(m >= (bits <= 24 ? FLT_MIN : DBL_MIN))) return 0;
    frexp(m, &e); /* m = f 2^e, f in [0.5, 1): the spacing is 2^(e - bits) */
    return fabs(a - b) / ldexp(1.0, e - bits);
}
