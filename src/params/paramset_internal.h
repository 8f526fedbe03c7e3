/*
 * Internal: lookups of a parameter list by name and type. pbrt-v2's ParamSet
 * keeps one list per type, so parameters of one name and different types
 * ("texture Kd" and "rgb Kd") live side by side; mt_paramset_find gives the
 * first of a name, this the one of a type.
 */
#ifndef MT_PARAMS_PARAMSET_INTERNAL_H
#define MT_PARAMS_PARAMSET_INTERNAL_H

#include "materia/params.h"

/* The parameter called name of the given type, or NULL. */
const mt_param *mt__paramset_find_type(const mt_paramset *ps, const char *name, mt_param_type type);

#endif
