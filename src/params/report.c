/* Errors and warnings with a location, and array growth, for src/params. */
#include <limits.h>
#include <stdio.h>
#include "core/alloc.h"
#include "params/report.h"

mt_status mt__fail_at(mt_error *err, mt_status status, const char *file, int line, int column,
                      const char *fmt, ...)
{
    va_list ap;
    if (!err) return status;
    mt_error_clear(err);
    err->status = status;
    va_start(ap, fmt);
    vsnprintf(err->message, sizeof err->message, fmt, ap);
    va_end(ap);
    mt_error_locate(err, file, line, column);
    return status;
}

void mt__warnf(mt_warning_fn warn, void *ctx, const char *file, int line, const char *fmt, ...)
{
    char msg[512];
    va_list ap;
    if (!warn) return;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    warn(ctx, file, line, msg);
}

void *mt__grow(void *p, int *cap, int need, size_t size)
{
    int ncap = *cap;
    void *np;
    if (need <= ncap) return p;
    if (need > INT_MAX / 2 || (size_t)need > (size_t)-1 / 2 / size) return NULL;
    ncap = ncap * 2 > need ? ncap * 2 : need;
    if (ncap < 8) ncap = 8;
    np = mt__realloc(p, (size_t)ncap * size);
    if (np) *cap = ncap;
    return np;
}
