/*
 * materia/parser.h -- pbrt-v2's scene-description syntax: a tokenizer and a
 * statement reader shared by the scene parser and the query tool.
 *
 * Comments (# to end of line), quoted strings, bracketed and bare values,
 * statements spanning lines, and Include (relative to the including file's
 * directory; pbrt-v2 resolves it against the main file's) are handled here;
 * each statement is delivered to a callback with its positional arguments
 * and its parameter list, built as pbrt-v2's InitParamSet builds it (colours
 * of every kind converted to RGB, SPD files read relative to the statement's
 * directory). Unknown directives, missing arguments, unterminated strings or
 * brackets, malformed numbers (pbrt-v2's syntax has no NaN or Inf literals;
 * values beyond float's range are errors) and binary garbage are errors that
 * name file, line and column and say what was expected. The parser never
 * crashes on any input. docs/PARSER.md lists what is accepted and where it
 * is stricter than pbrt-v2.
 *
 * Thread safety: the parse functions may run in any number of threads at
 * once; each calls back on the thread that called it.
 */
#ifndef MATERIA_PARSER_H
#define MATERIA_PARSER_H

#include "materia/params.h"

#ifdef __cplusplus
extern "C" {
#endif

/* A positional argument: a number or a string. */
typedef struct mt_arg {
    int is_string;
    double number;
    const char *string;
} mt_arg;

typedef struct mt_statement {
    const char *directive; /* "Texture", "Translate", "Shape", ... as written */
    int nargs;             /* positional arguments, in order */
    const mt_arg *args;    /* e.g. Texture: name, type, class; LookAt: 9 numbers;
                              Transform/ConcatTransform: 16 numbers */
    const mt_paramset *params; /* never NULL (empty when the directive has none) */
    const char *file;      /* the file (or stream name) the statement came from */
    const char *dir;       /* its directory, for relative file names */
    int line, column;      /* where the directive starts */
} mt_statement;

/* Called once per statement, in order, on the thread that called the parse
 * function; st and everything it points to are valid during the call only
 * (copy what must stay, or retain the paramset by cloning it). err has been
 * reset. A non-OK return stops parsing and is returned by the parse function
 * (err should then say why: the parser adds the statement's location when
 * err has none, and a message naming the directive when it has no message). */
typedef mt_status (*mt_statement_fn)(void *ctx, const mt_statement *st, mt_error *err);

typedef struct mt_parse_options {
    mt_warning_fn warn; /* may be NULL */
    void *warn_ctx;
    int max_include_depth; /* 0: 32 (pbrt-v2's limit); at most 1024 */
} mt_parse_options;

/* Parses the file at path, calling fn for each statement. opt may be NULL
 * (no warnings, the default include depth). MT_OK, the callback's status,
 * or an error of the parser's: MT_ERR_IO (an unreadable file, named),
 * MT_ERR_PARSE (malformed text, with line and column), MT_ERR_INVALID (a
 * parameter's values), MT_ERR_LIMIT (includes nested too deep). */
MT_API mt_status mt_parse_file(const char *path, const mt_parse_options *opt,
                               mt_statement_fn fn, void *ctx, mt_error *err);

/* As mt_parse_file for text: name is used in messages (NULL: "<string>"),
 * dir resolves Include and file names (NULL: the current directory),
 * first_line numbers the text's first line. */
MT_API mt_status mt_parse_string(const char *text, const char *name, const char *dir,
                                 int first_line, const mt_parse_options *opt,
                                 mt_statement_fn fn, void *ctx, mt_error *err);

/* 1 when text ends inside a bracket or a quoted string (more lines needed
 * to complete the statement), 0 otherwise -- also when the text is malformed
 * before its end, so that parsing it reports the error. Comments are
 * honoured. */
MT_API int mt_parse_incomplete(const char *text);

/* 1 when word is a directive of pbrt-v2's scene language. */
MT_API int mt_is_directive(const char *word);

#ifdef __cplusplus
}
#endif

#endif
