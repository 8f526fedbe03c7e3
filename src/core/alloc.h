/*
 * Internal: every heap allocation of the library goes through these, so that
 * tests can count allocations (a render must not allocate per sample) and
 * make the n-th allocation fail (every failure path must be clean).
 */
#ifndef MT_CORE_ALLOC_H
#define MT_CORE_ALLOC_H

#include <stddef.h>

void *mt__malloc(size_t size);
void *mt__calloc(size_t n, size_t size);
void *mt__realloc(void *p, size_t size);
void mt__free(void *p);
char *mt__strdup(const char *s);
/* The largest single request (in bytes) since the last reset: a test reads
 * a hostile file and proves that nothing big was asked for. reset: return
 * it and start again from 0. */
size_t mt__alloc_largest(int reset);

#endif
