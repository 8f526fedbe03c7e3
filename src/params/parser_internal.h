/* Internal: mt_parse_string for text that may hold NUL bytes (the tests
 * feed it binary data this way). */
#ifndef MT_PARAMS_PARSER_INTERNAL_H
#define MT_PARAMS_PARSER_INTERNAL_H

#include "materia/parser.h"

mt_status mt__parse_bytes(const char *text, size_t len, const char *name, const char *dir,
                          int first_line, const mt_parse_options *opt, mt_statement_fn fn,
                          void *ctx, mt_error *err);

/* mt_parse_incomplete, with *st = MT_ERR_NOMEM when the question could
 * not be answered for want of memory (MT_OK otherwise). */
int mt__parse_incomplete(const char *text, mt_status *st);

#endif
