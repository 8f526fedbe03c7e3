/*
 * Internal: file names relative to a directory (pbrt-v2 fileutil.cpp
 * ResolveFilename: absolute names are kept, relative ones are joined to the
 * directory), and whole-file reads.
 */
#ifndef MT_PARAMS_PATH_H
#define MT_PARAMS_PATH_H

#include <stddef.h>
#include "materia/error.h"

/* out = name when it is absolute or dir is NULL or empty, else dir/name.
 * MT_ERR_LIMIT when the result does not fit in size bytes. */
mt_status mt__path_join(const char *dir, const char *name, char *out, size_t size,
                        mt_error *err);

/* The directory part of path ("." when it has none, "/" for the root); a
 * new string, NULL when memory is exhausted. */
char *mt__path_dir(const char *path);

/* Reads the file at path into a new NUL-terminated buffer (*len excludes the
 * terminator; the content may hold NUL bytes). Errors name the file. */
mt_status mt__read_file(const char *path, char **data, size_t *len, mt_error *err);

#endif
