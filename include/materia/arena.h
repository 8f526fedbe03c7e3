/*
 * materia/arena.h -- the memory arena, with pbrt-v2's MemoryArena semantics.
 *
 * Allocations come from large blocks, rounded up to 16 bytes so that every
 * pointer is 16-byte aligned. Reset makes every block available again without
 * freeing it, so a renderer that resets once per camera sample stops calling
 * malloc after the first few samples. A request larger than the block size
 * gets a block of its own. Each thread owns its own arena.
 *
 * Thread safety: an arena belongs to one thread at a time: give each
 * thread its own (the BSDFs built in one may then be read by any thread
 * while it lives).
 */
#ifndef MATERIA_ARENA_H
#define MATERIA_ARENA_H

#include <stddef.h>
#include "materia/real.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mt_arena mt_arena;

/* A new arena whose blocks hold block_size bytes (0: pbrt-v2's 32768).
 * NULL when memory is exhausted. mt_arena_destroy frees it and everything
 * allocated from it. */
MT_API mt_arena *mt_arena_create(size_t block_size);
MT_API void mt_arena_destroy(mt_arena *a);

/* size bytes, 16-byte aligned, valid until the next mt_arena_reset or
 * mt_arena_destroy; NULL when memory is exhausted. Never freed alone. */
MT_API void *mt_arena_alloc(mt_arena *a, size_t size);

/* pbrt-v2 MemoryArena::FreeAll: everything allocated from the arena (BxDFs,
 * BSDFs) becomes invalid, and every block available for reuse. */
MT_API void mt_arena_reset(mt_arena *a);

/* Statistics: blocks obtained from malloc so far, and bytes they hold. */
MT_API size_t mt_arena_blocks(const mt_arena *a);
MT_API size_t mt_arena_bytes(const mt_arena *a);

#ifdef __cplusplus
}
#endif

#endif
