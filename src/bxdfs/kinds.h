/* Internal: helpers shared by the BxDF kinds. */
#ifndef MT_BXDFS_KINDS_H
#define MT_BXDFS_KINDS_H

#include "materia/bxdf.h"

/* Creators reject NaN and infinite parameters with a message naming them. */
static inline int mt__check_real(mt_real v, const char *param, const char *kind, mt_error *err)
{
    if (mt_is_finite(v)) return 1;
    mt_error_param(err, MT_ERR_INVALID, param, "%s: %s is not a finite number", kind, param);
    return 0;
}

static inline int mt__check_rgb(mt_rgb v, const char *param, const char *kind, mt_error *err)
{
    if (mt_rgb_is_finite(v)) return 1;
    mt_error_param(err, MT_ERR_INVALID, param, "%s: %s has a component that is not finite",
                   kind, param);
    return 0;
}

int mt__check_fresnel(const mt_fresnel *f, const char *kind, mt_error *err);
int mt__check_distribution(const mt_distribution *d, const char *kind, mt_error *err);

#endif
