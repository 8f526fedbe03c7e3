/*
 * The tokenizer of pbrt-v2's scene language, after pbrtlex.ll:
 *   WHITESPACE [ \t\r]+ and newlines; "#" to the end of the line;
 *   NUMBER [-+]?([0-9]+|(([0-9]+\.[0-9]*)|(\.[0-9]+)))([eE][-+]?[0-9]+)?
 *   IDENT  [a-zA-Z_][a-zA-Z_0-9]*
 *   "[" "]" and quoted strings with the escapes \n \t \r \b \f \" \\, \ddd
 *   (three decimal digits, reduced below 257 as pbrt-v2 does), backslash-
 *   newline (nothing), and backslash before any other character (that
 *   character).
 * Differences, each an error here where pbrt-v2 splits or goes on: a run of
 * number/identifier characters must be one whole NUMBER or IDENT ("1.5.3",
 * "0x10", "1e" are malformed rather than two tokens); a number that would be
 * infinite as a float (pbrt-v2 reads (float)atof) is out of range; a NUL byte
 * is never accepted; and an unterminated string stops the parse.
 */
#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include "core/alloc.h"
#include "params/numcheck.h"
#include "params/report.h"
#include "params/tokenizer.h"

void mt__lexer_init(mt__lexer *lx, const char *src, size_t len, const char *name,
                    int first_line)
{
    memset(lx, 0, sizeof *lx);
    lx->src = src;
    lx->len = len;
    lx->name = name;
    lx->line = first_line > 0 ? first_line : 1;
    lx->column = 1;
    /* a UTF-8 byte-order mark is not text */
    if (len >= 3 && memcmp(src, "\xEF\xBB\xBF", 3) == 0) lx->pos = 3;
}

void mt__lexer_free(mt__lexer *lx)
{
    mt__free(lx->buf);
    lx->buf = NULL;
    lx->buf_len = lx->buf_cap = 0;
}

static int buf_put(mt__lexer *lx, char c)
{
    if (lx->buf_len + 2 > lx->buf_cap) {
        size_t ncap = lx->buf_cap ? lx->buf_cap * 2 : 256;
        char *nb = mt__realloc(lx->buf, ncap);
        if (!nb) return 0;
        lx->buf = nb;
        lx->buf_cap = ncap;
    }
    lx->buf[lx->buf_len++] = c;
    lx->buf[lx->buf_len] = '\0';
    return 1;
}

static void advance(mt__lexer *lx)
{
    if (lx->src[lx->pos] == '\n') {
        lx->line++;
        lx->column = 1;
    } else {
        lx->column++;
    }
    lx->pos++;
}

static int is_digit(char c) { return c >= '0' && c <= '9'; }
static int is_alpha(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
static int is_word_char(char c) { return is_alpha(c) || is_digit(c) || c == '.' || c == '+' || c == '-'; }

/* pbrt-v2's NUMBER, matched against the whole word. */
static int is_number(const char *s, size_t n)
{
    size_t i = 0, whole = 0, frac = 0, expo = 0;
    if (i < n && (s[i] == '+' || s[i] == '-')) i++;
    for (; i < n && is_digit(s[i]); ++i) whole++;
    if (i < n && s[i] == '.')
        for (++i; i < n && is_digit(s[i]); ++i) frac++;
    if (whole + frac == 0) return 0;
    if (i < n && (s[i] == 'e' || s[i] == 'E')) {
        if (++i < n && (s[i] == '+' || s[i] == '-')) i++;
        for (; i < n && is_digit(s[i]); ++i) expo++;
        if (expo == 0) return 0;
    }
    return i == n;
}

static int is_ident(const char *s, size_t n)
{
    size_t i;
    if (n == 0 || !is_alpha(s[0])) return 0;
    for (i = 1; i < n; ++i)
        if (!is_alpha(s[i]) && !is_digit(s[i])) return 0;
    return 1;
}

int mt__is_nonfinite_word(const char *w)
{
    static const char *const names[] = {"nan", "inf", "infinity"};
    size_t k, i;
    if (*w == '+' || *w == '-') w++;
    for (k = 0; k < 3; ++k) {
        const char *n = names[k];
        for (i = 0; n[i] && w[i] && (w[i] | 0x20) == n[i]; ++i) {}
        if (!n[i] && !w[i]) return 1;
    }
    return 0;
}

static mt_status lex_word(mt__lexer *lx, mt__token *tok, mt_error *err)
{
    const char *w;
    char *end;
    while (lx->pos < lx->len && is_word_char(lx->src[lx->pos])) {
        if (lx->buf_len >= MT__MAX_WORD)
            return mt__fail_at(err, MT_ERR_PARSE, lx->name, tok->line, tok->column,
                             "token longer than %d characters", MT__MAX_WORD);
        if (!buf_put(lx, lx->src[lx->pos]))
            return mt__fail_at(err, MT_ERR_NOMEM, lx->name, tok->line, tok->column, "out of memory");
        advance(lx);
    }
    w = lx->buf;
    tok->text = w;
    tok->len = lx->buf_len;
    if (is_ident(w, lx->buf_len)) {
        tok->kind = MT_TOK_WORD;
        return MT_OK;
    }
    if (!is_number(w, lx->buf_len)) {
        if (mt__is_nonfinite_word(w))
            return mt__fail_at(err, MT_ERR_PARSE, lx->name, tok->line, tok->column,
                             "\"%s\" is not a number: pbrt-v2's syntax has no NaN or infinity",
                             w);
        return mt__fail_at(err, MT_ERR_PARSE, lx->name, tok->line, tok->column,
                         "malformed number \"%.60s\"", w);
    }
    errno = 0;
    tok->number = strtod(w, &end);
    if (end != w + lx->buf_len)
        return mt__fail_at(err, MT_ERR_PARSE, lx->name, tok->line, tok->column,
                         "cannot convert \"%.60s\" (is the C locale's decimal point '.'?)", w);
    if (!mt__fits_real(tok->number))
        return mt__fail_at(err, MT_ERR_PARSE, lx->name, tok->line, tok->column,
                         "number %.60s is out of range: it overflows to infinity as a float", w);
    tok->kind = MT_TOK_NUMBER;
    return MT_OK;
}

/* The escapes of pbrt-v2's STR state; pos is at the backslash. */
static mt_status lex_escape(mt__lexer *lx, mt__token *tok, mt_error *err, int *skip)
{
    const char *s = lx->src + lx->pos;
    size_t left = lx->len - lx->pos;
    int line = lx->line, column = lx->column;
    char c;
    *skip = 0;
    if (left < 2) {
        lx->eof_in_string = 1;
        return mt__fail_at(err, MT_ERR_PARSE, lx->name, tok->line, tok->column,
                         "unterminated string: the input ends inside it");
    }
    advance(lx);
    switch (s[1]) {
    case 'n': c = '\n'; break;
    case 't': c = '\t'; break;
    case 'r': c = '\r'; break;
    case 'b': c = '\b'; break;
    case 'f': c = '\f'; break;
    case '\n': /* backslash-newline continues the string on the next line */
        advance(lx);
        *skip = 1;
        return MT_OK;
    case '\r':
        if (left >= 3 && s[2] == '\n') {
            advance(lx);
            advance(lx);
            *skip = 1;
            return MT_OK;
        }
        c = '\r';
        break;
    case '\0':
        return mt__fail_at(err, MT_ERR_PARSE, lx->name, line, column, "NUL byte inside a string");
    default:
        if (left >= 4 && is_digit(s[1]) && is_digit(s[2]) && is_digit(s[3])) {
            /* pbrt-v2: atoi of the three digits, less 256 while above 256 */
            int v = (s[1] - '0') * 100 + (s[2] - '0') * 10 + (s[3] - '0');
            while (v > 256) v -= 256;
            if (v == 0 || v == 256)
                return mt__fail_at(err, MT_ERR_PARSE, lx->name, line, column,
                                 "escape \\%.3s makes a NUL byte inside a string", s + 1);
            advance(lx);
            advance(lx);
            c = (char)(unsigned char)v;
        } else {
            c = s[1]; /* \" \\ and any other character stand for themselves */
        }
        break;
    }
    advance(lx);
    if (!buf_put(lx, c)) return mt__fail_at(err, MT_ERR_NOMEM, lx->name, line, column, "out of memory");
    return MT_OK;
}

static mt_status lex_string(mt__lexer *lx, mt__token *tok, mt_error *err)
{
    advance(lx); /* the opening quote */
    if (!buf_put(lx, '\0')) return mt__fail_at(err, MT_ERR_NOMEM, lx->name, tok->line, tok->column, "out of memory");
    lx->buf_len = 0;
    for (;;) {
        char c;
        if (lx->pos >= lx->len) {
            lx->eof_in_string = 1;
            return mt__fail_at(err, MT_ERR_PARSE, lx->name, tok->line, tok->column,
                             "unterminated string: the input ends inside it");
        }
        if (lx->buf_len >= MT__MAX_STRING)
            return mt__fail_at(err, MT_ERR_PARSE, lx->name, tok->line, tok->column,
                             "string longer than %d bytes", MT__MAX_STRING);
        c = lx->src[lx->pos];
        if (c == '"') {
            advance(lx);
            break;
        }
        if (c == '\n')
            return mt__fail_at(err, MT_ERR_PARSE, lx->name, tok->line, tok->column,
                             "unterminated string: a string cannot continue past the end of "
                             "its line (write \\n, or end the line with a backslash)");
        if (c == '\0')
            return mt__fail_at(err, MT_ERR_PARSE, lx->name, lx->line, lx->column,
                             "NUL byte inside a string");
        if (c == '\\') {
            int skip;
            mt_status st = lex_escape(lx, tok, err, &skip);
            if (st != MT_OK) return st;
            continue;
        }
        if (!buf_put(lx, c))
            return mt__fail_at(err, MT_ERR_NOMEM, lx->name, tok->line, tok->column, "out of memory");
        advance(lx);
    }
    tok->kind = MT_TOK_STRING;
    tok->text = lx->buf;
    tok->len = lx->buf_len;
    return MT_OK;
}

mt_status mt__lex(mt__lexer *lx, mt__token *tok, mt_error *err)
{
    memset(tok, 0, sizeof *tok);
    lx->eof_in_string = 0;
    lx->buf_len = 0;
    if (lx->buf) lx->buf[0] = '\0';
    for (;;) {
        char c;
        if (lx->pos >= lx->len) {
            tok->kind = MT_TOK_EOF;
            tok->line = lx->line;
            tok->column = lx->column;
            tok->text = "";
            return MT_OK;
        }
        c = lx->src[lx->pos];
        if (c == ' ' || c == '\t' || c == '\r' || c == '\n') {
            advance(lx);
        } else if (c == '#') {
            while (lx->pos < lx->len && lx->src[lx->pos] != '\n') advance(lx);
        } else {
            break;
        }
    }
    tok->line = lx->line;
    tok->column = lx->column;
    if (lx->src[lx->pos] == '[' || lx->src[lx->pos] == ']') {
        int open = lx->src[lx->pos] == '[';
        advance(lx);
        tok->kind = open ? MT_TOK_LBRACK : MT_TOK_RBRACK;
        tok->text = open ? "[" : "]";
        tok->len = 1;
        return MT_OK;
    }
    if (lx->src[lx->pos] == '"') return lex_string(lx, tok, err);
    if (is_word_char(lx->src[lx->pos])) return lex_word(lx, tok, err);
    {
        unsigned char c = (unsigned char)lx->src[lx->pos];
        if (c == 0)
            return mt__fail_at(err, MT_ERR_PARSE, lx->name, tok->line, tok->column,
                             "unexpected NUL byte (binary data in a scene file?)");
        if (c >= 0x21 && c < 0x7f)
            return mt__fail_at(err, MT_ERR_PARSE, lx->name, tok->line, tok->column,
                             "unexpected character '%c' (0x%02x)", c, c);
        return mt__fail_at(err, MT_ERR_PARSE, lx->name, tok->line, tok->column,
                         "unexpected byte 0x%02x outside a string", c);
    }
}
