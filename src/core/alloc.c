/* The library's one allocator: counting and fault injection for tests. */
#include <stdlib.h>
#include <string.h>
#include "materia/tools/alloc.h"
#include "core/alloc.h"

static unsigned long alloc_count;
static long fail_countdown = -1;
static size_t largest_request;

static int should_fail(size_t size)
{
    size_t seen = __atomic_load_n(&largest_request, __ATOMIC_RELAXED);
    __atomic_add_fetch(&alloc_count, 1, __ATOMIC_RELAXED);
    while (size > seen && !__atomic_compare_exchange_n(&largest_request, &seen, size, 1,
                                                       __ATOMIC_RELAXED, __ATOMIC_RELAXED)) {
    }
    if (fail_countdown < 0) return 0;
    if (fail_countdown == 0) {
        fail_countdown = -1;
        return 1;
    }
    fail_countdown--;
    return 0;
}

unsigned long mt_alloc_count(void) { return __atomic_load_n(&alloc_count, __ATOMIC_RELAXED); }
void mt_alloc_fail_after(long n) { fail_countdown = n < 0 ? -1 : n; }
size_t mt__alloc_largest(int reset)
{
    return reset ? __atomic_exchange_n(&largest_request, 0, __ATOMIC_RELAXED)
                 : __atomic_load_n(&largest_request, __ATOMIC_RELAXED);
}

void *mt__malloc(size_t size) { return should_fail(size) ? NULL : malloc(size ? size : 1); }
void *mt__calloc(size_t n, size_t size)
{
    /* an overflowing product counts as the largest request there is */
    size_t bytes = size && n > (size_t)-1 / size ? (size_t)-1 : n * size;
    return should_fail(bytes) ? NULL : calloc(n ? n : 1, size ? size : 1);
}
void *mt__realloc(void *p, size_t size) { return should_fail(size) ? NULL : realloc(p, size ? size : 1); }
void mt__free(void *p) { free(p); }

char *mt__strdup(const char *s)
{
    size_t n = strlen(s) + 1;
    char *d = mt__malloc(n);
    if (d) memcpy(d, s, n);
    return d;
}
