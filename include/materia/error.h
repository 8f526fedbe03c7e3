/*
 * materia/error.h -- status codes and error messages.
 *
 * The library never prints, exits or aborts: a function that can fail
 * returns an mt_status (or NULL) and, when given an mt_error, fills it with a
 * message that names the file, line and parameter concerned when they are
 * known. What to do with the message is the caller's decision.
 *
 * The contract, for every function of materia that takes an mt_error *err:
 *  - err may be NULL: the function behaves the same and reports only through
 *    its return value.
 *  - On entry the function resets *err (status MT_OK, every string empty,
 *    line and column 0), so an mt_error may be reused across any number of
 *    calls: after a success it reads MT_OK with no message, after a failure
 *    it holds that failure's status, message, file, line, column and
 *    parameter and nothing of an earlier call. One exception, stated where it
 *    is declared: mt_bsdf_add given a NULL BSDF or BxDF (a failed creator)
 *    keeps the creator's error and returns its status.
 *  - An mt_error that no function has filled yet must be initialized before
 *    it is read: declare it `mt_error err = MT_ERROR_INIT;` (C and C++), or
 *    call mt_error_clear(&err). A function that takes &err initializes it, so
 *    `mt_error err;` followed by a call is also safe to read.
 *  - The message is complete in itself ("plastic material: ..."); the file,
 *    line, column and parameter are given apart so that a program can point
 *    at them. mt_error_format puts them together.
 *
 * Thread safety: an mt_error belongs to the thread that passes it; the
 * functions below only touch the mt_error they are given.
 */
#ifndef MATERIA_ERROR_H
#define MATERIA_ERROR_H

#include <stddef.h>
#include "materia/real.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum mt_status {
    MT_OK = 0,
    MT_ERR_INVALID,     /* an argument or parameter value is not acceptable */
    MT_ERR_NOMEM,       /* an allocation failed */
    MT_ERR_LIMIT,       /* a fixed capacity would be exceeded (e.g. 8 BxDFs) */
    MT_ERR_IO,          /* a file could not be opened, read or written */
    MT_ERR_PARSE,       /* malformed text input */
    MT_ERR_FORMAT,      /* malformed binary or data file */
    MT_ERR_UNSUPPORTED, /* valid pbrt-v2 input that materia does not implement
                           (a "cone" shape, a "volpath" integrator) */
    MT_ERR_NOT_FOUND    /* no such name: an unknown material type or texture
                           class, an undefined named texture or material */
} mt_status;

typedef struct mt_error {
    mt_status status;
    char file[256];  /* empty when unknown */
    int line;        /* 0 when unknown */
    int column;      /* 0 when unknown */
    char param[64];  /* the parameter concerned, empty when none */
    char message[512];
} mt_error;

/* An mt_error with status MT_OK and every field empty:
 *   mt_error err = MT_ERROR_INIT;
 * Every field is listed, so C++ compilers do not warn of missing ones. */
#define MT_ERROR_INIT {MT_OK, {0}, 0, 0, {0}, {0}}

/* The name of a status code ("ok", "invalid argument", ...); "unknown
 * status" for a value outside the enumeration. A static string. */
MT_API const char *mt_status_string(mt_status s);

/* Resets err as a function of materia does on entry: status MT_OK, empty
 * strings, line and column 0 (the same as assigning MT_ERROR_INIT). err may
 * be NULL. */
MT_API void mt_error_clear(mt_error *err);

/* The functions below are for code that reports errors through materia's
 * conventions (a BxDF or texture of one's own). They do not reset err first.
 *
 * mt_error_set: records status and a printf-style message (cut to fit) and
 * returns status; file, line, column and parameter are left as they are.
 * err may be NULL (then only status is returned). */
MT_API mt_status mt_error_set(mt_error *err, mt_status status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* As mt_error_set, naming the parameter concerned (NULL: none). */
MT_API mt_status mt_error_param(mt_error *err, mt_status status, const char *param,
                                const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

/* Sets the location: file (NULL: unknown), line and column (0: unknown). */
MT_API void mt_error_locate(mt_error *err, const char *file, int line, int column);

/* Writes "file:line:column: parameter "p": message" into buf, with only the
 * parts that are known (the status's name when there is no message), cut to
 * size bytes and always terminated when size > 0; returns buf. err NULL gives
 * "". It reads at most each field's size, so even a never-initialized err
 * cannot make it read past the struct (its output would then be garbage:
 * initialize with MT_ERROR_INIT). */
MT_API const char *mt_error_format(const mt_error *err, char *buf, size_t size);

#ifdef __cplusplus
}
#endif

#endif
