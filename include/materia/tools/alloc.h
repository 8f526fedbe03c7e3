/*
 * materia/tools/alloc.h -- allocation statistics and fault injection, for tests.
 *
 * Every heap allocation the library makes goes through one function. The
 * counter lets a test prove that rendering does not allocate per sample; the
 * fault injector lets a test make the n-th allocation fail and check that the
 * failure is reported cleanly and nothing leaks. The counter is atomic; the
 * injector is meant for single-threaded tests.
 *
 * Thread safety: the counter is atomic; the fault injector is for single-
 * threaded tests (set it while no other thread allocates).
 */
#ifndef MATERIA_TOOLS_ALLOC_H
#define MATERIA_TOOLS_ALLOC_H

#include <stddef.h>
#include "materia/real.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Allocations (malloc, calloc, realloc) made by the library so far. */
MT_API unsigned long mt_alloc_count(void);

/* Makes the allocation after n more succeed fail (n = 0: the next one), or
 * disables injection when n < 0. */
MT_API void mt_alloc_fail_after(long n);

#ifdef __cplusplus
}
#endif

#endif
