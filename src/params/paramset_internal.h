/*
 * Internal: what the library asks of a parameter list beyond params.h.
 * pbrt-v2's ParamSet keeps one list per type, so parameters of one name and
 * different types ("texture Kd" and "rgb Kd") live side by side;
 * mt_paramset_find gives the first of a name, mt__paramset_find_type the one
 * of a type.
 */
#ifndef MT_PARAMS_PARAMSET_INTERNAL_H
#define MT_PARAMS_PARAMSET_INTERNAL_H

#include "materia/params.h"

/* The parameter called name of the given type, or NULL. */
const mt_param *mt__paramset_find_type(const mt_paramset *ps, const char *name, mt_param_type type);

/* The first parameter no lookup used, in the order mt_paramset_report_unused
 * reports them (pbrt-v2's); NULL when every one was used or ps is NULL. */
const mt_param *mt__paramset_first_unused(const mt_paramset *ps);

/* The rule of the embedding entry points (mt_material_from_text and the
 * like): ps's unused parameters go to warn, one warning each; without warn
 * the first is an error (MT_ERR_INVALID naming it, at its line), so that a
 * misspelt name is never silently ignored. what names the statement or
 * object in the message ("plastic material"). */
mt_status mt__params_check_unused(const mt_paramset *ps, mt_warning_fn warn, void *ctx,
                                  const char *what, mt_error *err);

/* A new paramset holding copies of params[0 .. n-1] (n may be 0); NULL with
 * err naming the bad parameter. */
mt_paramset *mt__paramset_from_list(const mt_param *params, int n, mt_error *err);

#endif
