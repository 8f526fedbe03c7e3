/*
 * The memory arena (pbrt-v2 memory.h MemoryArena): bump allocation from
 * blocks, 16-byte rounding, and a reset that keeps every block for reuse.
 */
#include <stdint.h>
#include <stdlib.h>
#include "materia/arena.h"
#include "core/alloc.h"

typedef struct block {
    struct block *next;
    size_t size;
    /* the payload follows, at the first 16-byte boundary */
} block;

struct mt_arena {
    size_t block_size;
    block *current;   /* the block allocations come from */
    size_t pos;       /* offset of the next allocation in current */
    block *used;      /* full blocks, since the last reset */
    block *available; /* blocks free for reuse */
    size_t nblocks, nbytes;
};

static block *new_block(mt_arena *a, size_t size)
{
    block *b = mt__malloc(sizeof(block) + 15 + size);
    if (!b) return NULL;
    b->next = NULL;
    b->size = size;
    a->nblocks++;
    a->nbytes += size;
    return b;
}

static char *payload(block *b)
{
    uintptr_t p = (uintptr_t)(b + 1);
    return (char *)((p + 15) & ~(uintptr_t)15);
}

mt_arena *mt_arena_create(size_t block_size)
{
    mt_arena *a = mt__malloc(sizeof *a);
    if (!a) return NULL;
    a->block_size = block_size ? (block_size + 15) & ~(size_t)15 : 32768;
    a->pos = 0;
    a->used = a->available = NULL;
    a->nblocks = a->nbytes = 0;
    a->current = new_block(a, a->block_size);
    if (!a->current) {
        mt__free(a);
        return NULL;
    }
    return a;
}

static void free_list(block *b)
{
    while (b) {
        block *next = b->next;
        mt__free(b);
        b = next;
    }
}

void mt_arena_destroy(mt_arena *a)
{
    if (!a) return;
    mt__free(a->current);
    free_list(a->used);
    free_list(a->available);
    mt__free(a);
}

void *mt_arena_alloc(mt_arena *a, size_t size)
{
    void *ret;
    if (size > SIZE_MAX / 2) return NULL;
    size = (size + 15) & ~(size_t)15;
    if (a->pos + size > a->current->size) {
        /* pbrt-v2 retires the current block and takes an available one when
         * the request fits a standard block, else a new block of
         * max(size, block_size). Available blocks are never smaller than
         * block_size, so any of them serves a standard request. */
        block *next = NULL;
        if (size <= a->block_size && a->available) {
            next = a->available;
            a->available = next->next;
        } else {
            next = new_block(a, size > a->block_size ? size : a->block_size);
            if (!next) return NULL;
        }
        a->current->next = a->used;
        a->used = a->current;
        a->current = next;
        a->current->next = NULL;
        a->pos = 0;
    }
    ret = payload(a->current) + a->pos;
    a->pos += size;
    return ret;
}

void mt_arena_reset(mt_arena *a)
{
    a->pos = 0;
    while (a->used) {
        block *b = a->used;
        a->used = b->next;
        b->next = a->available;
        a->available = b;
    }
}

size_t mt_arena_blocks(const mt_arena *a) { return a->nblocks; }
size_t mt_arena_bytes(const mt_arena *a) { return a->nbytes; }
