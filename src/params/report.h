/*
 * Internal: the params layer's errors and warnings -- a formatted message at
 * a file, line and column -- and growth of its arrays.
 */
#ifndef MT_PARAMS_REPORT_H
#define MT_PARAMS_REPORT_H

#include <stdarg.h>
#include "materia/params.h"

/* Resets err (may be NULL) to status with the formatted message, located at
 * file:line:column (0 for unknown); returns status. */
mt_status mt__fail_at(mt_error *err, mt_status status, const char *file, int line, int column,
                      const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 6, 7)))
#endif
    ;

/* Formats a warning and hands it to warn (NULL: dropped). */
void mt__warnf(mt_warning_fn warn, void *ctx, const char *file, int line, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 5, 6)))
#endif
    ;

/* Room for need (> 0) elements of size bytes: p itself when *cap suffices,
 * else p reallocated to twice the capacity (at least need, at least 8) with
 * *cap updated; NULL when out of memory (p is then untouched and valid). */
void *mt__grow(void *p, int *cap, int need, size_t size);

#endif
