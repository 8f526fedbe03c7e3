/*
 * Internal: a parameter as a scene declares it -- "type name" and its values
 * -- checked and converted as pbrt-v2's InitParamSet (pbrtparse.yy) and the
 * ParamSet::Add* functions do, and added to a list.
 */
#ifndef MT_PARAMS_DECL_H
#define MT_PARAMS_DECL_H

#include "materia/params.h"

typedef struct mt__decl_values {
    const double *nums; /* the numbers given, or NULL */
    int nnums;
    const char *const *strs; /* the strings given, or NULL */
    int nstrs;
} mt__decl_values;

/* Where the declaration was written; dir resolves SPD file names. */
typedef struct mt__decl_site {
    const char *file;
    int line, column;
    const char *dir;
} mt__decl_site;

/* Adds the parameter declared by decl ("float roughness", "rgb Kd", ...)
 * with values to ps. Errors name the parameter and the site. */
mt_status mt__param_declare(mt_paramset *ps, const char *decl, const mt__decl_values *v,
                            const mt__decl_site *site, mt_error *err);

/* The name part of a declaration ("Kd" of "rgb Kd") into out, or "" when
 * decl is malformed. */
void mt__decl_name(const char *decl, char *out, size_t size);

#endif
