/*
 * Internal: the tokens of pbrt-v2's scene language (pbrtlex.ll): quoted
 * strings with their escapes, numbers, bare words (directives and keywords),
 * brackets; '#' starts a comment that runs to the end of the line.
 */
#ifndef MT_PARAMS_TOKENIZER_H
#define MT_PARAMS_TOKENIZER_H

#include <stddef.h>
#include "materia/error.h"

/* Limits that keep hostile input cheap: pbrt-v2 itself overflows a 1024-byte
 * buffer on longer strings. */
#define MT__MAX_STRING 65536
#define MT__MAX_WORD 1024

typedef enum mt__tok_kind {
    MT_TOK_EOF,
    MT_TOK_STRING, /* text: the decoded string */
    MT_TOK_NUMBER, /* number: its value; text: as written */
    MT_TOK_WORD,   /* text: an identifier ([A-Za-z_][A-Za-z_0-9]*) */
    MT_TOK_LBRACK,
    MT_TOK_RBRACK
} mt__tok_kind;

typedef struct mt__token {
    mt__tok_kind kind;
    const char *text; /* NUL-terminated; valid until the next mt__lex */
    size_t len;
    double number;
    int line, column; /* where the token starts (1-based; columns count bytes) */
} mt__token;

typedef struct mt__lexer {
    const char *src;
    size_t len, pos;
    int line, column;
    const char *name; /* the file or stream name, for messages */
    char *buf;        /* the current token's text */
    size_t buf_len, buf_cap;
    int eof_in_string; /* the last error: input ended inside a string */
} mt__lexer;

void mt__lexer_init(mt__lexer *lx, const char *src, size_t len, const char *name,
                    int first_line);
void mt__lexer_free(mt__lexer *lx);

/* The next token. Errors (malformed input) name the file, line and column;
 * err may be NULL. */
mt_status mt__lex(mt__lexer *lx, mt__token *tok, mt_error *err);

/* Whether word, ignoring a sign and case, is nan, inf or infinity. */
int mt__is_nonfinite_word(const char *word);

#endif
