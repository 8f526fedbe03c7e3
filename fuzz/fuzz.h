/*
 * The fuzz targets' shared part. Each target (target_*.c) defines
 * LLVMFuzzerTestOneInput: libFuzzer calls it when the target is built with
 * clang -fsanitize=fuzzer (make fuzz); driver.c calls it once per corpus
 * file when it is built with any compiler (make check).
 *
 * The readers under test take file names, so the input is written to a
 * file of the process's own temporary directory first.
 */
#ifndef MT_FUZZ_H
#define MT_FUZZ_H

#include <stddef.h>
#include <stdint.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* The process's temporary directory (created on first use, removed with
 * its files at exit). NULL when it cannot be created. */
const char *fz_dir(void);

/* Writes data to fz_dir()/input<ext> and returns that path, or NULL. */
const char *fz_write_input(const uint8_t *data, size_t size, const char *ext);

/* data as a NUL-terminated string (a NUL in data ends it early); the
 * buffer is the caller's to free(). */
char *fz_text(const uint8_t *data, size_t size);

#endif
