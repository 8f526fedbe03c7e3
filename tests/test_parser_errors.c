/*
 * Broken scene text: each input gives a clean error with its file, line and
 * column and a message that says what was expected -- never a crash. Then a
 * deterministic fuzz loop (random bytes, random token soup) and allocation
 * failures injected at every allocation of a parse: the parser must come
 * back every time, with an error or without (ASan/UBSan watch in CI).
 */
#include <stdlib.h>
#include <string.h>
#include "materia/parser.h"
#include "params/parser_internal.h"
#include "support/check.h"
#include "support/tfiles.h"

/* A statement callback that uses its parameters the way consumers do:
 * lookups of every kind (some fail), a clone, the unused report. */
static void ignore_warning(void *ctx, const char *file, int line, const char *message) {}

static mt_status consume(void *ctx, const mt_statement *st, mt_error *err)
{
    int i, n = mt_paramset_count(st->params);
    mt_paramset *copy = mt_paramset_clone(st->params);
    if (!copy) return mt_error_set(err, MT_ERR_NOMEM, "clone");
    for (i = 0; i < n; ++i) {
        const mt_param *p = mt_paramset_at(st->params, i);
        mt_real f;
        mt_rgb c;
        const char *s;
        const double *a;
        int k;
        mt_error e;
        mt_params_float(copy, p->name, 0, &f, &e);
        mt_params_rgb(copy, p->name, mt_rgb_black(), &c, &e);
        mt_params_string(copy, p->name, "", &s, &e);
        mt_params_points(copy, p->name, &a, &k, &e);
    }
    mt_paramset_report_unused(copy, ignore_warning, NULL);
    mt_paramset_destroy(copy);
    return MT_OK;
}

typedef struct bad_input {
    const char *text;
    int line, column;
    const char *word;
} bad_input;

static const bad_input bads[] = {
    {"Shape \"sphere", 1, 7, "unterminated string"},
    {"Shape \"sph\nere\"", 1, 7, "unterminated string"},
    {"Shape \"abc\\", 1, 7, "unterminated string"},
    {"Shape \"s\" \"float r\" [1 2\n", 1, 21, "unterminated [ list"},
    {"WorldBegin\n  Foo \"x\"", 2, 3, "unknown directive \"Foo\""},
    {"texture \"t\" \"float\" \"constant\"", 1, 1, "case-sensitive: Texture"},
    {"Translate 1 \"a\" 3", 1, 13, "expected 3 numbers"},
    {"Translate 1 2\nWorldBegin", 2, 1, "directive WorldBegin"},
    {"Texture \"a\" \"float\"", 1, 20, "3 quoted strings"},
    {"Transform [1 0 0 0 0 1 0 0 0 0 1 0 0 0 0]", 1, 11, "16 numbers, found 15"},
    {"ConcatTransform 1 0 0", 1, 17, "[ list ] of 16 numbers"},
    {"Translate 1e39 0 0", 1, 11, "out of range"},
    {"Translate 0 3.5e38 0", 1, 13, "out of range"},
    {"Translate 0 0 1e400", 1, 15, "out of range"},
    {"Shape \"s\" \"float r\" -1e39", 1, 21, "out of range"},
    {"Translate nan 0 0", 1, 11, "NaN or infinity"},
    {"Translate 0 -inf 0", 1, 13, "NaN or infinity"},
    {"Shape \"s\" \"float r\" [Infinity]", 1, 22, "NaN or infinity"},
    {"Translate 1.5.3 0 0", 1, 11, "malformed number"},
    {"Scale 0x10 1 1", 1, 7, "malformed number"},
    {"Scale 1e 1 1", 1, 7, "malformed number"},
    {"Shape \"s\" , \"float r\" 1", 1, 11, "unexpected character ','"},
    {"Shape \"s\" \"float r\"\nWorldBegin", 2, 1, "expected a value"},
    {"Shape \"s\" \"float r\" [1 [2]]", 1, 24, "do not nest"},
    {"Shape \"s\" \"float r\" [1 \"a\"]", 1, 24, "a string in a list of numbers"},
    {"Shape \"s\" \"string r\" [\"a\" 2]", 1, 27, "a number in a list of strings"},
    {"WorldBegin \"x\"", 1, 12, "no parameter list"},
    {"WorldBegin 5", 1, 12, "expected a directive"},
    {"Shape \"s\" ]", 1, 11, "expected a \"type name\" parameter or a directive"},
    {"Shape \"s\" \"bool b\" true", 1, 20, "quoted strings: \"true\""},
    {"ActiveTransform Foo", 1, 17, "All, StartTime or EndTime"},
    {"ActiveTransform", 1, 16, "All, StartTime or EndTime"},
    {"Shape \"s\" \"float r\" []", 1, 11, "has no values"},
    {"NamedMaterial \"a\" \"b\"", 1, 19, "no parameter list"},
    {"Shape \"a\\000b\"", 1, 9, "NUL byte"},
    {"Shape \"a\\256b\"", 1, 9, "NUL byte"},
    {"WorldBegin \x01", 1, 12, "unexpected byte 0x01"},
    {"WorldBegin\n\x80\x81", 2, 1, "unexpected byte 0x80"},
    {"[ 1 2 ]", 1, 1, "expected a directive"},
    {"\"float r\" 1", 1, 1, "expected a directive"},
    {"Include \"/nonexistent/materia/x.pbrt\"", 1, 1, "cannot open"},
    {"Include 3", 1, 9, "a quoted string"},
};

static void test_bad_inputs(void)
{
    size_t i;
    for (i = 0; i < sizeof bads / sizeof bads[0]; ++i) {
        mt_error err;
        char name[160];
        mt_status rc = mt_parse_string(bads[i].text, "bad.pbrt", NULL, 1, NULL, consume, NULL, &err);
        snprintf(name, sizeof name, "error %d: %.50s", (int)i, bads[i].word);
        t_check(rc != MT_OK && strcmp(err.file, "bad.pbrt") == 0 && err.line == bads[i].line &&
                    err.column == bads[i].column && strstr(err.message, bads[i].word) != NULL,
                name, "got %s:%d:%d: %s", err.file, err.line, err.column, err.message);
    }
}

/* Writes rel, parses it: the error must be in a file whose name holds where
 * (NULL: rel), at line:column, with word in the message. */
static void check_file_error(const char *rel, const char *text, size_t len, const char *where,
                             int line, int column, const char *word, const char *name)
{
    mt_error err;
    const char *path = t_write_file(rel, text, len);
    char file[1024];
    mt_status rc;
    snprintf(file, sizeof file, "%s", path ? path : "");
    rc = mt_parse_file(file, NULL, consume, NULL, &err);
    t_check(rc != MT_OK && strstr(err.file, where ? where : rel) != NULL && err.line == line &&
                err.column == column && strstr(err.message, word) != NULL,
            name, "got %s:%d:%d: %s", err.file, err.line, err.column, err.message);
}

static char *repeat(char c, size_t n, const char *before, const char *after)
{
    size_t a = strlen(before), b = strlen(after);
    char *s = malloc(a + n + b + 1);
    memcpy(s, before, a);
    memset(s + a, c, n);
    memcpy(s + a + n, after, b + 1);
    return s;
}

static void test_files(void)
{
    char *s;
    int i;
    mt_error err;
    mt_parse_options opt;
    const char *dir = t_tmpdir_create("parser-errors");
    mt_status rc;
    if (!dir) {
        t_fail("files: temp dir", "cannot create");
        return;
    }
    check_file_error("nul.pbrt", "WorldBegin\n\0Shape", 17, NULL, 2, 1, "NUL byte", "embedded NUL");
    check_file_error("nulstr.pbrt", "Shape \"ab\0c\"", 12, NULL, 1, 10, "NUL byte inside a string",
                     "NUL inside a string");
    check_file_error("bin.pbrt", "\x7f" "ELF\x02\x01\x01", 7, NULL, 1, 1, "unexpected byte 0x7f",
                     "binary garbage");
    check_file_error("bom.pbrt", "\xEF\xBB\xBFWorldBegin Foo", (size_t)-1, NULL, 1, 12,
                     "unknown directive", "a byte-order mark is skipped");
    s = repeat('a', 5000, "", "");
    check_file_error("word.pbrt", s, (size_t)-1, NULL, 1, 1, "longer than", "a 5000-character word");
    free(s);
    s = repeat('7', 3000, "Translate ", " 0 0");
    check_file_error("digits.pbrt", s, (size_t)-1, NULL, 1, 11, "longer than", "a 3000-digit number");
    free(s);
    s = repeat('x', 70000, "Shape \"", "\"");
    check_file_error("string.pbrt", s, (size_t)-1, NULL, 1, 7, "longer than", "a 70000-byte string");
    free(s);
    /* Include cycles and depth */
    t_write_file("cyc/a.pbrt", "WorldBegin\nInclude \"b.pbrt\"", (size_t)-1);
    t_write_file("cyc/b.pbrt", "\n Include \"a.pbrt\"", (size_t)-1);
    check_file_error("cyc/a.pbrt", "WorldBegin\nInclude \"b.pbrt\"", (size_t)-1, "cyc/b.pbrt", 2, 2,
                     "includes itself", "an Include cycle (the error in the file that closes it)");
    check_file_error("self.pbrt", "Include \"self.pbrt\"", (size_t)-1, NULL, 1, 1, "includes itself",
                     "a file including itself");
    for (i = 0; i < 40; ++i) {
        char rel[64], text[64];
        snprintf(rel, sizeof rel, "deep/%d.pbrt", i);
        snprintf(text, sizeof text, "Include \"%d.pbrt\"", i + 1);
        t_write_file(rel, text, (size_t)-1);
    }
    t_write_file("deep/40.pbrt", "WorldBegin", (size_t)-1);
    check_file_error("deep/0.pbrt", "Include \"1.pbrt\"", (size_t)-1, "deep/32.pbrt", 1, 1,
                     "more than 32 levels",
                     "Include deeper than 32 levels");
    memset(&opt, 0, sizeof opt);
    opt.max_include_depth = 45;
    rc = mt_parse_file(t_write_file("deep/0.pbrt", "Include \"1.pbrt\"", (size_t)-1), &opt,
                       consume, NULL, &err);
    t_check(rc == MT_OK, "Include depth limit is an option", "%s", err.message);
    rc = mt_parse_file(dir, NULL, consume, NULL, &err);
    t_check(rc == MT_ERR_IO && strstr(err.message, "not a regular file"),
            "parsing a directory: an I/O error", "%d %s", rc, err.message);
    rc = mt_parse_file("/nonexistent/materia.pbrt", NULL, consume, NULL, &err);
    t_check(rc == MT_ERR_IO && strcmp(err.file, "/nonexistent/materia.pbrt") == 0,
            "a missing file: an I/O error naming it", "%d %s", rc, err.message);
    t_tmpdir_remove();
}

/* xorshift64*: a fixed sequence, so that a failure can be replayed. */
static unsigned long long rng_state = 0x9E3779B97F4A7C15ull;
static unsigned rnd(unsigned n)
{
    rng_state ^= rng_state >> 12;
    rng_state ^= rng_state << 25;
    rng_state ^= rng_state >> 27;
    return (unsigned)((rng_state * 2685821657736338717ull) >> 33) % n;
}

static int parse_bytes(const char *text, size_t len)
{
    mt_error err;
    mt_status rc = mt__parse_bytes(text, len, "fuzz", NULL, 1, NULL, consume, NULL, &err);
    return rc == MT_OK || (err.status == rc && err.message[0]);
}

static void fuzz_bytes(void)
{
    static const char alphabet[] = "  \n\t\"\"[]#\\0123456789.-+eE_aAzZ,@\x01\xff\xc3";
    char buf[400];
    int i, ok = 1;
    for (i = 0; i < 3000; ++i) {
        size_t n = rnd(sizeof buf), k;
        for (k = 0; k < n; ++k)
            buf[k] = rnd(8) == 0 ? (char)rnd(256) : alphabet[rnd(sizeof alphabet - 1)];
        if (!parse_bytes(buf, n)) ok = 0;
        if (n) buf[n - 1] = '\0';
        (void)mt_parse_incomplete(buf);
    }
    t_check(ok, "fuzz: 3000 random byte strings, every error reported", "an error without a message");
}

static void fuzz_tokens(void)
{
    static const char *const words[] = {
        "Shape", "Texture", "Material", "MakeNamedMaterial", "NamedMaterial", "LookAt",
        "Transform", "ConcatTransform", "Rotate", "Scale", "Translate", "AttributeBegin",
        "AttributeEnd", "ActiveTransform", "All", "EndTime", "WorldBegin", "WorldEnd",
        "Include \"/nonexistent/fuzz.pbrt\"", "\"float a\"", "\"integer b\"", "\"bool c\"",
        "\"string d\"", "\"point e\"", "\"rgb f\"", "\"xyz g\"", "\"blackbody h\"",
        "\"spectrum i\"", "\"texture j\"", "\"normal k\"", "\"vector l\"", "\"point3 m\"",
        "\"true\"", "\"false\"", "\"x\\ty\"", "\"\\101\"", "\"\"", "\"unterminated", "[", "]",
        "[", "]", "0", "1", "-2.5", ".5", "1e38", "1e39", "6500", "400", "nan", "inf", "1.2.3",
        "#", "\n", "\n", "\\", "Foo", "spds/none.spd", "\"spds/none.spd\"", "3e9", "0.5",
    };
    char buf[4096];
    int i, ok = 1;
    for (i = 0; i < 3000; ++i) {
        size_t len = 0;
        int t, n = 1 + (int)rnd(40);
        for (t = 0; t < n; ++t) {
            const char *w = words[rnd(sizeof words / sizeof words[0])];
            size_t wl = strlen(w);
            if (len + wl + 2 >= sizeof buf) break;
            memcpy(buf + len, w, wl);
            len += wl;
            buf[len++] = rnd(4) ? ' ' : '\n';
        }
        buf[len] = '\0';
        if (!parse_bytes(buf, len)) ok = 0;
        (void)mt_parse_incomplete(buf);
    }
    t_check(ok, "fuzz: 3000 random token soups, every error reported", "an error without a message");
}

/* A valid scene that uses every kind of value. */
static const char scene[] =
    "LookAt 0 0 5 0 0 0 0 1 0 Camera \"perspective\" \"float fov\" [45]\n"
    "WorldBegin AttributeBegin\n"
    "Texture \"t\" \"color\" \"checkerboard\" \"rgb tex1\" [1 0 0] \"string aamode\" \"none\"\n"
    "Material \"plastic\" \"texture Kd\" \"t\" \"xyz Ks\" [0.3 0.3 0.3]\n"
    "  \"spectrum eta\" [400 1.5 700 1.4] \"blackbody L\" [3000 1] \"bool b\" \"true\"\n"
    "Shape \"trianglemesh\" \"integer indices\" [0 1 2] \"point P\" [0 0 0 1 0 0 0 1 0]\n"
    "Transform [1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1] Rotate 30 0 0 1 # \"comment\"\n"
    "AttributeEnd WorldEnd\n";

/* The valid scene with a few bytes replaced, deleted or inserted: errors deep
 * inside statements and parameter lists. */
static void fuzz_mutations(void)
{
    static const char bytes[] = "\"[]#\\ \n0.e-+aZ\0\xff";
    char buf[sizeof scene + 16];
    int i, ok = 1, good = 0;
    for (i = 0; i < 3000; ++i) {
        size_t len = sizeof scene - 1;
        int m, edits = 1 + (int)rnd(3);
        memcpy(buf, scene, len);
        for (m = 0; m < edits; ++m) {
            size_t at = rnd((unsigned)len);
            char c = bytes[rnd(sizeof bytes - 1)];
            switch (rnd(3)) {
            case 0: buf[at] = c; break;
            case 1: memmove(buf + at, buf + at + 1, len - at - 1); len--; break;
            default: memmove(buf + at + 1, buf + at, len - at); buf[at] = c; len++; break;
            }
        }
        if (!parse_bytes(buf, len)) ok = 0;
        if (mt__parse_bytes(buf, len, "m", NULL, 1, NULL, NULL, NULL, NULL) == MT_OK) good++;
    }
    t_check(ok && good > 100 && good < 2900, "fuzz: 3000 mutations of a valid scene",
            "%d parsed; errors reported: %d", good, ok);
}

/* Every allocation of a representative parse fails in turn: each run ends
 * with MT_OK or MT_ERR_NOMEM, and nothing leaks (ASan checks). */
static void test_alloc_failures(void)
{
    const char *text = scene;
    long n;
    int bad = 0, failed_runs = 0;
    for (n = 0; n < 2000; ++n) {
        mt_error err;
        mt_status rc;
        mt_alloc_fail_after(n);
        rc = mt_parse_string(text, "alloc.pbrt", NULL, 1, NULL, consume, NULL, &err);
        mt_alloc_fail_after(-1);
        if (rc == MT_OK) break;
        failed_runs++;
        if (rc != MT_ERR_NOMEM) {
            bad++;
            printf("# allocation %ld: %d %s\n", n, rc, err.message);
        }
    }
    t_check(bad == 0 && n < 2000 && failed_runs > 20,
            "allocation failures: every one reported as out of memory", "%d wrong of %d runs",
            bad, failed_runs);
}

int main(void)
{
    test_bad_inputs();
    test_files();
    fuzz_bytes();
    fuzz_tokens();
    fuzz_mutations();
    test_alloc_failures();
    return t_status();
}
