/* Status codes and error messages: the library reports, the caller decides. */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include "materia/error.h"

const char *mt_status_string(mt_status s)
{
    switch (s) {
    case MT_OK: return "ok";
    case MT_ERR_INVALID: return "invalid argument";
    case MT_ERR_NOMEM: return "out of memory";
    case MT_ERR_LIMIT: return "limit exceeded";
    case MT_ERR_IO: return "input/output error";
    case MT_ERR_PARSE: return "parse error";
    case MT_ERR_FORMAT: return "malformed data";
    case MT_ERR_UNSUPPORTED: return "unsupported";
    case MT_ERR_NOT_FOUND: return "not found";
    }
    return "unknown status";
}

/* Field by field rather than memset: every function that takes an mt_error
 * calls this on entry, among them mt_material_get_bsdf once per shading
 * point, and the strings only need their first byte. */
void mt_error_clear(mt_error *err)
{
    if (!err) return;
    err->status = MT_OK;
    err->file[0] = '\0';
    err->line = 0;
    err->column = 0;
    err->param[0] = '\0';
    err->message[0] = '\0';
}

static void vset(mt_error *err, mt_status status, const char *fmt, va_list ap)
{
    err->status = status;
    vsnprintf(err->message, sizeof err->message, fmt, ap);
}

mt_status mt_error_set(mt_error *err, mt_status status, const char *fmt, ...)
{
    va_list ap;
    if (!err) return status;
    va_start(ap, fmt);
    vset(err, status, fmt, ap);
    va_end(ap);
    return status;
}

mt_status mt_error_param(mt_error *err, mt_status status, const char *param, const char *fmt,
                         ...)
{
    va_list ap;
    if (!err) return status;
    snprintf(err->param, sizeof err->param, "%s", param ? param : "");
    va_start(ap, fmt);
    vset(err, status, fmt, ap);
    va_end(ap);
    return status;
}

void mt_error_locate(mt_error *err, const char *file, int line, int column)
{
    if (!err) return;
    snprintf(err->file, sizeof err->file, "%s", file ? file : "");
    err->line = line;
    err->column = column;
}

const char *mt_error_format(const mt_error *err, char *buf, size_t size)
{
    size_t n = 0;
    if (!buf || size == 0) return buf;
    buf[0] = '\0';
    if (!err) return buf;
#define APPEND(...)                                                         \
    do {                                                                    \
        int w_ = snprintf(buf + n, n < size ? size - n : 0, __VA_ARGS__);   \
        if (w_ > 0) n += (size_t)w_;                                        \
    } while (0)
    /* %.*s: a field that lost its terminator is still read within bounds */
    if (err->file[0]) {
        APPEND("%.*s:", (int)sizeof err->file - 1, err->file);
        if (err->line > 0) APPEND("%d:", err->line);
        if (err->column > 0) APPEND("%d:", err->column);
        APPEND(" ");
    }
    if (err->param[0]) APPEND("parameter \"%.*s\": ", (int)sizeof err->param - 1, err->param);
    if (err->message[0]) APPEND("%.*s", (int)sizeof err->message - 1, err->message);
    else APPEND("%s", mt_status_string(err->status));
#undef APPEND
    return buf;
}
