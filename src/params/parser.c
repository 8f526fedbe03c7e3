/*
 * pbrt-v2's scene grammar (pbrtparse.yy): a directive, its positional
 * arguments, and for most directives a parameter list of "type name" value
 * pairs, where a value is one number, one quoted string or a [ list ] of
 * either. Each statement goes to the caller's callback; Include is handled
 * here, relative to the including file, with a depth limit and a check for
 * files that include themselves.
 *
 * The parser keeps one token of lookahead: a parameter list ends where the
 * next token is not a quoted string, which is where the next directive must
 * begin.
 */
#include <errno.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>
#include "core/alloc.h"
#include "materia/parser.h"
#include "params/decl.h"
#include "params/numcheck.h"
#include "params/parser_internal.h"
#include "params/path.h"
#include "params/report.h"
#include "params/tokenizer.h"

/* Positional arguments: s a quoted string, n a number, a a [ list ] of 16
 * numbers, k one of the keywords All, StartTime, EndTime. */
typedef struct directive {
    const char *name;
    const char *args;
    int has_params;
} directive;

static const directive directives[] = {
    {"Accelerator", "s", 1},        {"ActiveTransform", "k", 0},
    {"AreaLightSource", "s", 1},    {"AttributeBegin", "", 0},
    {"AttributeEnd", "", 0},        {"Camera", "s", 1},
    {"ConcatTransform", "a", 0},    {"CoordinateSystem", "s", 0},
    {"CoordSysTransform", "s", 0},  {"Film", "s", 1},
    {"Identity", "", 0},            {"Include", "s", 0},
    {"LightSource", "s", 1},        {"LookAt", "nnnnnnnnn", 0},
    {"MakeNamedMaterial", "s", 1},  {"Material", "s", 1},
    {"NamedMaterial", "s", 0},      {"ObjectBegin", "s", 0},
    {"ObjectEnd", "", 0},           {"ObjectInstance", "s", 0},
    {"PixelFilter", "s", 1},        {"Renderer", "s", 1},
    {"ReverseOrientation", "", 0},  {"Rotate", "nnnn", 0},
    {"Sampler", "s", 1},            {"Scale", "nnn", 0},
    {"Shape", "s", 1},              {"SurfaceIntegrator", "s", 1},
    {"Texture", "sss", 1},          {"TransformBegin", "", 0},
    {"TransformEnd", "", 0},        {"TransformTimes", "nn", 0},
    {"Transform", "a", 0},          {"Translate", "nnn", 0},
    {"Volume", "s", 1},             {"VolumeIntegrator", "s", 1},
    {"WorldBegin", "", 0},          {"WorldEnd", "", 0},
};
#define N_DIRECTIVES (int)(sizeof directives / sizeof directives[0])
#define MAX_ARGS 16
#define MAX_STRING_ARGS 3
#define PATH_SIZE 4096

static const directive *find_directive(const char *word)
{
    int i;
    for (i = 0; i < N_DIRECTIVES; ++i)
        if (strcmp(directives[i].name, word) == 0) return &directives[i];
    return NULL;
}

int mt_is_directive(const char *word) { return word && find_directive(word) != NULL; }

/* A directive that differs from word only in case, for a hint, or NULL. */
static const directive *find_directive_nocase(const char *word)
{
    int i;
    size_t k;
    for (i = 0; i < N_DIRECTIVES; ++i) {
        const char *d = directives[i].name;
        for (k = 0; d[k] && word[k] && (d[k] | 0x20) == (word[k] | 0x20); ++k) {}
        if (!d[k] && !word[k]) return &directives[i];
    }
    return NULL;
}

/* A file being parsed, in the chain of Includes that led to it. */
typedef struct include_link {
    dev_t dev;
    ino_t ino;
    const struct include_link *up;
} include_link;

typedef struct parser {
    mt_warning_fn warn;
    void *warn_ctx;
    int max_depth;
    mt_statement_fn fn;
    void *ctx;
} parser;

/* One source (file or string) and the statement being read from it. */
typedef struct source {
    parser *P;
    mt__lexer lx;
    mt__token tok;
    const char *name, *dir;
    int depth;
    const include_link *chain;
    /* the statement */
    const directive *d;
    int line, column;
    mt_arg args[MAX_ARGS];
    int nargs;
    char *strs[MAX_STRING_ARGS];
    int nstrs;
    mt_paramset *params;
    /* the values of the parameter being read */
    double *nums;
    int nnums, cap_nums;
    char **vals;
    int nvals, cap_vals;
} source;

static mt_status parse_file_at(parser *P, const char *path, int depth, const include_link *chain,
                               mt_error *err);

static mt_status next(source *S, mt_error *err) { return mt__lex(&S->lx, &S->tok, err); }

/* The current token, described for a message. */
static const char *describe(const mt__token *t, char *buf, size_t size)
{
    switch (t->kind) {
    case MT_TOK_EOF: return "the end of the input";
    case MT_TOK_LBRACK: return "'['";
    case MT_TOK_RBRACK: return "']'";
    case MT_TOK_STRING: snprintf(buf, size, "the string \"%.40s\"", t->text); return buf;
    case MT_TOK_NUMBER: snprintf(buf, size, "the number %.40s", t->text); return buf;
    case MT_TOK_WORD:
        if (mt_is_directive(t->text))
            snprintf(buf, size, "the directive %s (the statement is incomplete)", t->text);
        else if (mt__is_nonfinite_word(t->text))
            snprintf(buf, size, "%.40s (pbrt-v2's syntax has no NaN or infinity)", t->text);
        else if (strcmp(t->text, "true") == 0 || strcmp(t->text, "false") == 0)
            snprintf(buf, size, "%s (bool values are quoted strings: \"%s\")", t->text, t->text);
        else
            snprintf(buf, size, "the bare word %.40s", t->text);
        return buf;
    }
    return "?";
}

static mt_status expected(source *S, mt_error *err, const char *what)
{
    char buf[160];
    return mt__fail_at(err, MT_ERR_PARSE, S->name, S->tok.line, S->tok.column, "%s: expected %s, found %s",
                     S->d ? S->d->name : "statement", what, describe(&S->tok, buf, sizeof buf));
}

/* What a directive's positional arguments are, for messages. */
static const char *args_text(const directive *d)
{
    size_t n = strlen(d->args);
    if (d->args[0] == 'a') return "a [ list ] of 16 numbers";
    if (d->args[0] == 'k') return "All, StartTime or EndTime";
    if (d->args[0] == 'n') {
        switch (n) {
        case 2: return "2 numbers";
        case 3: return "3 numbers";
        case 4: return "4 numbers (angle in degrees, then the axis)";
        default: return "9 numbers (eye, look-at point, up vector)";
        }
    }
    return n == 1 ? "a quoted string" : "3 quoted strings (name, type, class)";
}

static mt_status read_numbers_list(source *S, mt_error *err)
{
    int line = S->tok.line, column = S->tok.column, n = 0;
    mt_status st = next(S, err);
    while (st == MT_OK && S->tok.kind == MT_TOK_NUMBER) {
        if (n < MAX_ARGS) {
            S->args[n].is_string = 0;
            S->args[n].number = S->tok.number;
        }
        n++;
        st = next(S, err);
    }
    if (st != MT_OK) return st;
    if (S->tok.kind == MT_TOK_EOF)
        return mt__fail_at(err, MT_ERR_PARSE, S->name, line, column,
                         "%s: unterminated [ list: expected ']' before the end of the input",
                         S->d->name);
    if (S->tok.kind != MT_TOK_RBRACK) return expected(S, err, "a number or ']'");
    if (n != MAX_ARGS)
        return mt__fail_at(err, MT_ERR_PARSE, S->name, line, column,
                         "%s: expected a [ list ] of 16 numbers, found %d number%s", S->d->name,
                         n, n == 1 ? "" : "s");
    S->nargs = MAX_ARGS;
    return next(S, err);
}

static mt_status read_args(source *S, mt_error *err)
{
    const char *a;
    for (a = S->d->args; *a; ++a) {
        mt_arg *arg = &S->args[S->nargs];
        mt_status st;
        if (*a == 'a') {
            if (S->tok.kind != MT_TOK_LBRACK) return expected(S, err, args_text(S->d));
            return read_numbers_list(S, err);
        }
        if (*a == 'n') {
            if (S->tok.kind != MT_TOK_NUMBER) return expected(S, err, args_text(S->d));
            arg->is_string = 0;
            arg->number = S->tok.number;
        } else if (*a == 'k') {
            static const char *const keys[] = {"All", "StartTime", "EndTime"};
            int k;
            if (S->tok.kind != MT_TOK_WORD) return expected(S, err, args_text(S->d));
            for (k = 0; k < 3 && strcmp(S->tok.text, keys[k]) != 0; ++k) {}
            if (k == 3) return expected(S, err, args_text(S->d));
            arg->is_string = 1;
            arg->string = keys[k];
        } else {
            if (S->tok.kind != MT_TOK_STRING) return expected(S, err, args_text(S->d));
            S->strs[S->nstrs] = mt__strdup(S->tok.text);
            if (!S->strs[S->nstrs])
                return mt__fail_at(err, MT_ERR_NOMEM, S->name, S->tok.line, S->tok.column, "out of memory");
            arg->is_string = 1;
            arg->string = S->strs[S->nstrs++];
        }
        S->nargs++;
        st = next(S, err);
        if (st != MT_OK) return st;
    }
    return MT_OK;
}

static int push_num(source *S, double v)
{
    double *nums = S->nnums < MT__MAX_VALUES
                       ? mt__grow(S->nums, &S->cap_nums, S->nnums + 1, sizeof *nums)
                       : NULL;
    if (!nums) return 0;
    S->nums = nums;
    S->nums[S->nnums++] = v;
    return 1;
}

static int push_val(source *S, const char *s)
{
    char **vals = S->nvals < MT__MAX_VALUES
                      ? mt__grow(S->vals, &S->cap_vals, S->nvals + 1, sizeof *vals)
                      : NULL;
    if (!vals) return 0;
    S->vals = vals;
    if (!(S->vals[S->nvals] = mt__strdup(s))) return 0;
    S->nvals++;
    return 1;
}

static void clear_values(source *S)
{
    int i;
    for (i = 0; i < S->nvals; ++i) mt__free(S->vals[i]);
    S->nvals = S->nnums = 0;
}

/* One value token (a number or a string) into the value lists. */
static mt_status push_value(source *S, const char *decl, mt_error *err)
{
    int ok;
    if (S->tok.kind == MT_TOK_NUMBER && S->nvals)
        return mt__fail_at(err, MT_ERR_PARSE, S->name, S->tok.line, S->tok.column,
                         "\"%.80s\": a number in a list of strings", decl);
    if (S->tok.kind == MT_TOK_STRING && S->nnums)
        return mt__fail_at(err, MT_ERR_PARSE, S->name, S->tok.line, S->tok.column,
                         "\"%.80s\": a string in a list of numbers", decl);
    ok = S->tok.kind == MT_TOK_NUMBER ? push_num(S, S->tok.number) : push_val(S, S->tok.text);
    if (!ok)
        return mt__fail_at(err, MT_ERR_NOMEM, S->name, S->tok.line, S->tok.column,
                         "\"%.80s\": out of memory (or more than %d values)", decl, MT__MAX_VALUES);
    return next(S, err);
}

static mt_status read_list(source *S, const char *decl, mt_error *err)
{
    int line = S->tok.line, column = S->tok.column;
    mt_status st = next(S, err);
    while (st == MT_OK) {
        char buf[160];
        switch (S->tok.kind) {
        case MT_TOK_NUMBER:
        case MT_TOK_STRING: st = push_value(S, decl, err); break;
        case MT_TOK_RBRACK: return next(S, err);
        case MT_TOK_EOF:
            return mt__fail_at(err, MT_ERR_PARSE, S->name, line, column,
                             "\"%.80s\": unterminated [ list: expected ']' before the end of the "
                             "input", decl);
        case MT_TOK_LBRACK:
            return mt__fail_at(err, MT_ERR_PARSE, S->name, S->tok.line, S->tok.column,
                             "\"%.80s\": '[' inside a [ list ] (lists do not nest)", decl);
        default:
            return mt__fail_at(err, MT_ERR_PARSE, S->name, S->tok.line, S->tok.column,
                             "\"%.80s\": expected a number, a quoted string or ']', found %s",
                             decl, describe(&S->tok, buf, sizeof buf));
        }
    }
    return st;
}

/* "type name" value: the current token is the declaration string. */
static mt_status read_param(source *S, mt_error *err)
{
    mt__decl_site site;
    mt__decl_values v;
    char *decl = mt__strdup(S->tok.text), name[256], buf[160];
    mt_status st;
    site.file = S->name;
    site.line = S->tok.line;
    site.column = S->tok.column;
    site.dir = S->dir;
    if (!decl) return mt__fail_at(err, MT_ERR_NOMEM, S->name, site.line, site.column, "out of memory");
    clear_values(S);
    st = next(S, err);
    if (st == MT_OK) {
        if (S->tok.kind == MT_TOK_LBRACK)
            st = read_list(S, decl, err);
        else if (S->tok.kind == MT_TOK_NUMBER || S->tok.kind == MT_TOK_STRING)
            st = push_value(S, decl, err);
        else
            st = mt__fail_at(err, MT_ERR_PARSE, S->name, S->tok.line, S->tok.column,
                           "\"%.80s\": expected a value (a number, a quoted string or a [ list ]), "
                           "found %s", decl, describe(&S->tok, buf, sizeof buf));
    }
    if (st == MT_OK) {
        int before = mt_paramset_count(S->params), had;
        mt__decl_name(decl, name, sizeof name);
        had = name[0] && mt_paramset_find(S->params, name);
        v.nums = S->nums;
        v.nnums = S->nnums;
        v.strs = (const char *const *)S->vals;
        v.nstrs = S->nvals;
        st = mt__param_declare(S->params, decl, &v, &site, err);
        /* the list did not grow: it replaced one of its type (pbrt-v2 keeps
         * one list per type; "texture Kd" beside "rgb Kd" replaces nothing) */
        if (st == MT_OK && had && mt_paramset_count(S->params) == before)
            mt__warnf(S->P->warn, S->P->warn_ctx, S->name, site.line, "Parameter \"%s\" given twice in one %s statement; the last one is used",
                 name, S->d->name);
    }
    mt__free(decl);
    clear_values(S);
    return st;
}

static void reset_statement(source *S)
{
    int i;
    for (i = 0; i < S->nstrs; ++i) mt__free(S->strs[i]);
    S->nstrs = S->nargs = 0;
    mt_paramset_destroy(S->params);
    S->params = NULL;
    S->d = NULL;
}

/* Why path cannot be parsed (NULL when it is a regular file; sb filled). */
static const char *file_problem(const char *path, struct stat *sb)
{
    if (stat(path, sb) != 0) return strerror(errno);
    return S_ISREG(sb->st_mode) ? NULL : "not a regular file";
}

static mt_status do_include(source *S, const char *file, mt_error *err)
{
    char path[PATH_SIZE];
    struct stat sb;
    const include_link *l;
    include_link self;
    const char *problem;
    mt_error why;
    mt_error_clear(&why);
    if (mt__path_join(S->dir, file, path, sizeof path, &why) != MT_OK)
        return mt__fail_at(err, MT_ERR_LIMIT, S->name, S->line, S->column, "Include: %s", why.message);
    if (S->depth + 1 > S->P->max_depth)
        return mt__fail_at(err, MT_ERR_LIMIT, S->name, S->line, S->column,
                         "Include \"%.200s\": more than %d levels of nested Include", file,
                         S->P->max_depth);
    if ((problem = file_problem(path, &sb)) != NULL)
        return mt__fail_at(err, MT_ERR_IO, S->name, S->line, S->column,
                         "Include: cannot open \"%.200s\" (looked for \"%.200s\"): %s", file,
                         path, problem);
    for (l = S->chain; l; l = l->up)
        if (l->dev == sb.st_dev && l->ino == sb.st_ino)
            return mt__fail_at(err, MT_ERR_PARSE, S->name, S->line, S->column,
                             "Include \"%.200s\": the file includes itself (an Include cycle)",
                             file);
    self.dev = sb.st_dev;
    self.ino = sb.st_ino;
    self.up = S->chain;
    return parse_file_at(S->P, path, S->depth + 1, &self, err);
}

static mt_status deliver(source *S, mt_error *err)
{
    mt_statement st;
    mt_status rc;
    if (strcmp(S->d->name, "Include") == 0) return do_include(S, S->args[0].string, err);
    st.directive = S->d->name;
    st.nargs = S->nargs;
    st.args = S->args;
    st.params = S->params;
    st.file = S->name;
    st.dir = S->dir;
    st.line = S->line;
    st.column = S->column;
    mt_error_clear(err);
    rc = S->P->fn ? S->P->fn(S->P->ctx, &st, err) : MT_OK;
    if (rc != MT_OK) {
        if (err->status == MT_OK) err->status = rc;
        if (!err->message[0]) snprintf(err->message, sizeof err->message, "%s rejected", S->d->name);
        if (!err->file[0]) mt_error_locate(err, S->name, S->line, S->column);
    }
    return rc;
}

static mt_status statement(source *S, mt_error *err)
{
    char buf[160];
    mt_status st;
    if (S->tok.kind != MT_TOK_WORD || !(S->d = find_directive(S->tok.text))) {
        const directive *near = S->tok.kind == MT_TOK_WORD ? find_directive_nocase(S->tok.text) : NULL;
        if (near)
            return mt__fail_at(err, MT_ERR_PARSE, S->name, S->tok.line, S->tok.column,
                             "unknown directive \"%.60s\" (directives are case-sensitive: %s?)",
                             S->tok.text, near->name);
        if (S->tok.kind == MT_TOK_WORD && !mt__is_nonfinite_word(S->tok.text))
            return mt__fail_at(err, MT_ERR_PARSE, S->name, S->tok.line, S->tok.column,
                             "unknown directive \"%.60s\"", S->tok.text);
        return mt__fail_at(err, MT_ERR_PARSE, S->name, S->tok.line, S->tok.column,
                         "expected a directive, found %s", describe(&S->tok, buf, sizeof buf));
    }
    S->line = S->tok.line;
    S->column = S->tok.column;
    S->params = mt_paramset_create();
    if (!S->params) return mt__fail_at(err, MT_ERR_NOMEM, S->name, S->line, S->column, "out of memory");
    st = next(S, err);
    if (st == MT_OK) st = read_args(S, err);
    while (st == MT_OK && S->d->has_params && S->tok.kind == MT_TOK_STRING) st = read_param(S, err);
    if (st == MT_OK && !S->d->has_params && S->tok.kind == MT_TOK_STRING)
        st = mt__fail_at(err, MT_ERR_PARSE, S->name, S->tok.line, S->tok.column,
                       "%s takes %s and no parameter list: found %s", S->d->name,
                       S->d->args[0] ? args_text(S->d) : "no arguments",
                       describe(&S->tok, buf, sizeof buf));
    if (st == MT_OK && S->tok.kind != MT_TOK_WORD && S->tok.kind != MT_TOK_EOF)
        st = mt__fail_at(err, MT_ERR_PARSE, S->name, S->tok.line, S->tok.column,
                       "%s: expected %sa directive, found %s", S->d->name,
                       S->d->has_params ? "a \"type name\" parameter or " : "",
                       describe(&S->tok, buf, sizeof buf));
    if (st == MT_OK) st = deliver(S, err);
    reset_statement(S);
    return st;
}

static mt_status parse_source(parser *P, const char *text, size_t len, const char *name,
                              const char *dir, int first_line, int depth,
                              const include_link *chain, mt_error *err)
{
    source S;
    mt_status st;
    memset(&S, 0, sizeof S);
    S.P = P;
    S.name = name;
    S.dir = dir;
    S.depth = depth;
    S.chain = chain;
    mt__lexer_init(&S.lx, text, len, name, first_line);
    st = next(&S, err);
    while (st == MT_OK && S.tok.kind != MT_TOK_EOF) st = statement(&S, err);
    reset_statement(&S);
    clear_values(&S);
    mt__free(S.nums);
    mt__free(S.vals);
    mt__lexer_free(&S.lx);
    return st;
}

static mt_status parse_file_at(parser *P, const char *path, int depth, const include_link *chain,
                               mt_error *err)
{
    char *text, *dir;
    size_t len;
    mt_status st = mt__read_file(path, &text, &len, err);
    if (st != MT_OK) {
        mt_error_locate(err, path, 0, 0);
        return st;
    }
    dir = mt__path_dir(path);
    if (!dir) {
        mt__free(text);
        mt_error_locate(err, path, 0, 0);
        return mt_error_set(err, MT_ERR_NOMEM, "out of memory");
    }
    st = parse_source(P, text, len, path, dir, 1, depth, chain, err);
    mt__free(dir);
    mt__free(text);
    return st;
}

static void init_parser(parser *P, const mt_parse_options *opt, mt_statement_fn fn, void *ctx)
{
    P->warn = opt ? opt->warn : NULL;
    P->warn_ctx = opt ? opt->warn_ctx : NULL;
    P->fn = fn;
    P->ctx = ctx;
    P->max_depth = opt && opt->max_include_depth > 0 ? opt->max_include_depth : 32;
    if (P->max_depth > 1024) P->max_depth = 1024;
}

mt_status mt_parse_file(const char *path, const mt_parse_options *opt, mt_statement_fn fn,
                        void *ctx, mt_error *err)
{
    parser P;
    mt_error local;
    struct stat sb;
    include_link self;
    const char *why;
    if (!err) err = &local;
    mt_error_clear(err);
    if (!path) return mt_error_set(err, MT_ERR_INVALID, "no file name");
    init_parser(&P, opt, fn, ctx);
    if ((why = file_problem(path, &sb)) != NULL) {
        mt_error_locate(err, path, 0, 0);
        return mt_error_set(err, MT_ERR_IO, "cannot open \"%s\": %s", path, why);
    }
    self.dev = sb.st_dev;
    self.ino = sb.st_ino;
    self.up = NULL;
    return parse_file_at(&P, path, 0, &self, err);
}

mt_status mt__parse_bytes(const char *text, size_t len, const char *name, const char *dir,
                          int first_line, const mt_parse_options *opt, mt_statement_fn fn,
                          void *ctx, mt_error *err)
{
    parser P;
    mt_error local;
    if (!err) err = &local;
    mt_error_clear(err);
    if (!text) return mt_error_set(err, MT_ERR_INVALID, "no text");
    init_parser(&P, opt, fn, ctx);
    return parse_source(&P, text, len, name ? name : "<string>", dir, first_line, 0, NULL, err);
}

mt_status mt_parse_string(const char *text, const char *name, const char *dir, int first_line,
                          const mt_parse_options *opt, mt_statement_fn fn, void *ctx,
                          mt_error *err)
{
    return mt__parse_bytes(text, text ? strlen(text) : 0, name, dir, first_line, opt, fn, ctx,
                           err);
}

int mt__parse_incomplete(const char *text, mt_status *st)
{
    mt__lexer lx;
    mt__token tok;
    int open = 0, result;
    *st = MT_OK;
    if (!text) return 0;
    mt__lexer_init(&lx, text, strlen(text), "", 1);
    for (;;) {
        mt_status ls = mt__lex(&lx, &tok, NULL);
        if (ls != MT_OK) {
            if (ls == MT_ERR_NOMEM) *st = ls;
            result = lx.eof_in_string; /* any other error: complete, and wrong */
            break;
        }
        if (tok.kind == MT_TOK_EOF) {
            result = open;
            break;
        }
        if (tok.kind == MT_TOK_LBRACK) open = 1;
        if (tok.kind == MT_TOK_RBRACK) open = 0;
    }
    mt__lexer_free(&lx);
    return result;
}

int mt_parse_incomplete(const char *text)
{
    mt_status st;
    return mt__parse_incomplete(text, &st);
}
