/*
 * Parameters no one read, for the embedding entry points: a warning to the
 * caller's callback, or an error when there is none -- a misspelt "Kdd"
 * must reach the caller one way or the other, never be dropped.
 */
#include "params/paramset_internal.h"

mt_status mt__params_check_unused(const mt_paramset *ps, mt_warning_fn warn, void *ctx,
                                  const char *what, mt_error *err)
{
    const mt_param *p = mt__paramset_first_unused(ps);
    if (!p) return MT_OK;
    if (warn) {
        mt_paramset_report_unused(ps, warn, ctx);
        return MT_OK;
    }
    mt_error_param(err, MT_ERR_INVALID, p->name,
                   "%s: not used (a misspelt name, or a value of another type; with a warning "
                   "callback, mt_state_set_warning, it is a warning instead)", what);
    mt_error_locate(err, p->file, p->line, p->column);
    return MT_ERR_INVALID;
}

mt_paramset *mt__paramset_from_list(const mt_param *params, int n, mt_error *err)
{
    mt_paramset *ps;
    int i;
    if (n < 0 || (n > 0 && !params)) {
        mt_error_set(err, MT_ERR_INVALID, "a parameter list of %d parameters%s", n,
                     n > 0 ? " given as NULL" : "");
        return NULL;
    }
    ps = mt_paramset_create();
    if (!ps) {
        mt_error_set(err, MT_ERR_NOMEM, "out of memory for a parameter list");
        return NULL;
    }
    for (i = 0; i < n; ++i)
        if (mt_paramset_add(ps, &params[i], err) != MT_OK) {
            mt_paramset_destroy(ps);
            return NULL;
        }
    return ps;
}
