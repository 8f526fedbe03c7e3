/*
 * materia/error.h -- status codes and error messages.
 *
 * Fallible functions return an mt_status (or NULL) and fill an mt_error when
 * one is given. The library never prints, exits or aborts: the caller decides
 * what to do with the message. Messages name the file, line and parameter
 * when they are known.
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
    MT_ERR_UNSUPPORTED, /* valid input that materia does not implement */
    MT_ERR_NOT_FOUND    /* a named object does not exist */
} mt_status;

typedef struct mt_error {
    mt_status status;
    char file[256];  /* empty when unknown */
    int line;        /* 0 when unknown */
    int column;      /* 0 when unknown */
    char param[64];  /* the parameter concerned, empty when none */
    char message[512];
} mt_error;

/* The name of a status code ("ok", "invalid argument", ...). */
MT_API const char *mt_status_string(mt_status s);

/* Resets err to MT_OK with no message. err may be NULL. */
MT_API void mt_error_clear(mt_error *err);

/* Records status and a printf-style message; returns status. err may be NULL.
 * The file/line/param fields are left as they are. */
MT_API mt_status mt_error_set(mt_error *err, mt_status status, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* As mt_error_set, naming the parameter concerned. */
MT_API mt_status mt_error_param(mt_error *err, mt_status status, const char *param,
                                const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

/* Sets the location (file may be NULL; line/column 0 for unknown). */
MT_API void mt_error_locate(mt_error *err, const char *file, int line, int column);

/* Formats "file:line:column: parameter "p": message" into buf (the parts that
 * are known) and returns buf. */
MT_API const char *mt_error_format(const mt_error *err, char *buf, size_t size);

#ifdef __cplusplus
}
#endif

#endif
