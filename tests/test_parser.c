/*
 * The scene-language reader: tokens, strings and their escapes, comments,
 * statements over several lines with their locations, every directive's
 * arguments, Include, mt_parse_incomplete, and the shared reference scenes.
 */
#include <dirent.h>
#include <stdlib.h>
#include <string.h>
#include "materia/parser.h"
#include "support/check.h"
#include "support/tfiles.h"

/* What the callback saw, statement by statement. */
#define MAX_SEEN 64
typedef struct seen {
    char directive[32];
    int nargs;
    mt_arg args[16];
    char strs[3][128];
    int nparams;
    char file[512], dir[512];
    int line, column;
    mt_paramset *params;
} seen;

static seen log_[MAX_SEEN];
static int nlog, total;

static void reset_log(void)
{
    int i;
    for (i = 0; i < nlog; ++i) mt_paramset_destroy(log_[i].params);
    nlog = total = 0;
}

static mt_status record(void *ctx, const mt_statement *st, mt_error *err)
{
    seen *s;
    int i, k = 0;
    total++;
    if (nlog == MAX_SEEN) return MT_OK;
    s = &log_[nlog++];
    memset(s, 0, sizeof *s);
    snprintf(s->directive, sizeof s->directive, "%s", st->directive);
    s->nargs = st->nargs;
    for (i = 0; i < st->nargs && i < 16; ++i) {
        s->args[i] = st->args[i];
        if (st->args[i].is_string && k < 3) {
            snprintf(s->strs[k], sizeof s->strs[k], "%s", st->args[i].string);
            s->args[i].string = s->strs[k++];
        }
    }
    s->nparams = mt_paramset_count(st->params);
    s->params = mt_paramset_clone(st->params);
    snprintf(s->file, sizeof s->file, "%s", st->file ? st->file : "");
    snprintf(s->dir, sizeof s->dir, "%s", st->dir ? st->dir : "");
    s->line = st->line;
    s->column = st->column;
    return MT_OK;
}

static mt_status parse(const char *text, mt_error *err)
{
    reset_log();
    return mt_parse_string(text, "t.pbrt", NULL, 1, NULL, record, NULL, err);
}

static const char *param_string(const seen *s, const char *name)
{
    const char *v = NULL;
    mt_error err;
    if (mt_params_string(s->params, name, NULL, &v, &err) != MT_OK) return NULL;
    return v;
}

static void test_strings(void)
{
    mt_error err;
    mt_status rc = parse("Texture \"a\\tb\\n\" \"c\\\"q\\\\\" \"x\\101y\\300\"\n"
                         "  \"string cont\" \"one \\\ntwo\" \"string other\" \"\\q\\[\"\n"
                         "  \"string empty\" \"\" \"string high\" \"caf\xc3\xa9\"",
                         &err);
    const char *v;
    if (!t_check(rc == MT_OK && nlog == 1, "strings: parse", "%s", err.message)) return;
    t_check(strcmp(log_[0].args[0].string, "a\tb\n") == 0, "string escapes \\t \\n",
            "[%s]", log_[0].args[0].string);
    t_check(strcmp(log_[0].args[1].string, "c\"q\\") == 0, "string escapes \\\" \\\\", "[%s]",
            log_[0].args[1].string);
    /* pbrt-v2 reads \ddd as decimal, less 256 while above 256: \101 is 'e',
     * \300 is 44 (',') */
    t_check(strcmp(log_[0].args[2].string, "xey,") == 0, "string escape \\ddd is decimal",
            "[%s]", log_[0].args[2].string);
    v = param_string(&log_[0], "cont");
    t_check(v && strcmp(v, "one two") == 0, "backslash-newline continues a string", "[%s]",
            v ? v : "(null)");
    v = param_string(&log_[0], "other");
    t_check(v && strcmp(v, "q[") == 0, "backslash before another character: the character",
            "[%s]", v ? v : "(null)");
    v = param_string(&log_[0], "empty");
    t_check(v && v[0] == '\0', "empty string", "[%s]", v ? v : "(null)");
    v = param_string(&log_[0], "high");
    t_check(v && strcmp(v, "caf\xc3\xa9") == 0, "UTF-8 inside a string", "[%s]", v ? v : "(null)");
}

static void test_comments_numbers(void)
{
    mt_error err;
    const double *f = NULL;
    int n = 0;
    mt_status rc = parse("# a comment with \"quotes and [ brackets\nWorldBegin # after\n"
                         "Shape \"s\" \"float v\" [1 -2. .5 +3e2 1E-3 -0 0.000001e6]"
                         "# no newline at the end",
                         &err);
    t_check(rc == MT_OK && nlog == 2 && strcmp(log_[0].directive, "WorldBegin") == 0 &&
                log_[0].line == 2,
            "comments are skipped", "%d statements: %s", nlog, err.message);
    if (nlog == 2 && mt_params_floats(log_[1].params, "v", &f, &n, &err) == MT_OK && n == 7)
        t_check(f[0] == 1 && f[1] == -2 && f[2] == 0.5 && f[3] == 300 && f[4] == 1e-3 &&
                    f[5] == 0 && f[6] == 1,
                "numbers in every form pbrt-v2's lexer takes", "%g %g %g %g %g %g %g", f[0],
                f[1], f[2], f[3], f[4], f[5], f[6]);
    else
        t_fail("numbers in every form pbrt-v2's lexer takes", "n = %d: %s", n, err.message);
}

static void test_locations(void)
{
    mt_error err;
    mt_status rc = parse("\n  LookAt 0 0 5\n   0 0 0\n 0 1 0\nShape \"sphere\"\n"
                         "  \"float radius\" [\n 2\n ]\n\tAttributeBegin",
                         &err);
    const mt_param *p;
    if (!t_check(rc == MT_OK && nlog == 3, "multi-line statements: parse", "%d: %s", nlog,
                 err.message))
        return;
    t_check(log_[0].line == 2 && log_[0].column == 3 && log_[0].nargs == 9 &&
                log_[0].args[8].number == 0 && log_[0].args[7].number == 1,
            "LookAt over three lines", "%d:%d nargs %d", log_[0].line, log_[0].column,
            log_[0].nargs);
    p = mt_paramset_find(log_[1].params, "radius");
    t_check(log_[1].line == 5 && log_[1].column == 1 && p && p->line == 6 && p->column == 3 &&
                p->doubles[0] == 2 && strcmp(p->file, "t.pbrt") == 0,
            "a parameter list over three lines, located", "%d:%d", p ? p->line : 0,
            p ? p->column : 0);
    t_check(log_[2].line == 9 && log_[2].column == 2, "a tab counts one column", "%d:%d",
            log_[2].line, log_[2].column);
    reset_log();
    rc = mt_parse_string("\n\nWorldBegin", "q", NULL, 42, NULL, record, NULL, &err);
    t_check(rc == MT_OK && nlog == 1 && log_[0].line == 44, "first_line numbers the text",
            "%d", nlog ? log_[0].line : 0);
}

/* Every directive of pbrt-v2's grammar with its positional arguments. */
static void test_directives(void)
{
    static const struct {
        const char *name;
        const char *args; /* s string, n number */
        int nparams;
    } want[] = {
        {"Accelerator", "s", 1},     {"ActiveTransform", "s", 0},  {"ActiveTransform", "s", 0},
        {"ActiveTransform", "s", 0}, {"AreaLightSource", "s", 1},  {"AttributeBegin", "", 0},
        {"AttributeEnd", "", 0},     {"Camera", "s", 1},           {"ConcatTransform", "16", 0},
        {"CoordinateSystem", "s", 0}, {"CoordSysTransform", "s", 0}, {"Film", "s", 2},
        {"Identity", "", 0},         {"LightSource", "s", 1},      {"LookAt", "nnnnnnnnn", 0},
        {"MakeNamedMaterial", "s", 2}, {"Material", "s", 1},       {"NamedMaterial", "s", 0},
        {"ObjectBegin", "s", 0},     {"ObjectEnd", "", 0},         {"ObjectInstance", "s", 0},
        {"PixelFilter", "s", 0},     {"Renderer", "s", 0},         {"ReverseOrientation", "", 0},
        {"Rotate", "nnnn", 0},       {"Sampler", "s", 1},          {"Scale", "nnn", 0},
        {"Shape", "s", 1},           {"SurfaceIntegrator", "s", 1}, {"Texture", "sss", 2},
        {"TransformBegin", "", 0},   {"TransformEnd", "", 0},      {"TransformTimes", "nn", 0},
        {"Transform", "16", 0},      {"Translate", "nnn", 0},      {"Volume", "s", 1},
        {"VolumeIntegrator", "s", 0}, {"WorldBegin", "", 0},       {"WorldEnd", "", 0},
    };
    const char *text =
        "Accelerator \"bvh\" \"integer maxprims\" 4\n"
        "ActiveTransform StartTime ActiveTransform EndTime ActiveTransform All\n"
        "AreaLightSource \"area\" \"rgb L\" [1 1 1]\n"
        "AttributeBegin AttributeEnd\n"
        "Camera \"perspective\" \"float fov\" 45\n"
        "ConcatTransform [1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1]\n"
        "CoordinateSystem \"c\" CoordSysTransform \"c\"\n"
        "Film \"image\" \"integer xresolution\" 10 \"string filename\" \"a.exr\"\n"
        "Identity\n"
        "LightSource \"point\" \"point from\" [0 0 1]\n"
        "LookAt 1 2 3 4 5 6 7 8 9\n"
        "MakeNamedMaterial \"m\" \"string type\" \"matte\" \"rgb Kd\" [1 0 0]\n"
        "Material \"plastic\" \"float roughness\" 0.1\n"
        "NamedMaterial \"m\"\n"
        "ObjectBegin \"o\" ObjectEnd ObjectInstance \"o\"\n"
        "PixelFilter \"box\" Renderer \"sampler\" ReverseOrientation\n"
        "Rotate 90 0 0 1\n"
        "Sampler \"lowdiscrepancy\" \"integer pixelsamples\" 4\n"
        "Scale 1 2 3\n"
        "Shape \"sphere\" \"float radius\" 1\n"
        "SurfaceIntegrator \"path\" \"integer maxdepth\" 5\n"
        "Texture \"t\" \"color\" \"checkerboard\" \"rgb tex1\" [1 1 1] \"rgb tex2\" [0 0 0]\n"
        "TransformBegin TransformEnd TransformTimes 0 1\n"
        "Transform [2 0 0 0 0 2 0 0 0 0 2 0 1 2 3 1]\n"
        "Translate -1 -2 -3\n"
        "Volume \"homogeneous\" \"rgb sigma_a\" [1 1 1]\n"
        "VolumeIntegrator \"single\"\n"
        "WorldBegin WorldEnd\n";
    mt_error err;
    mt_status rc = parse(text, &err);
    size_t i, n = sizeof want / sizeof want[0];
    int all = 1;
    if (!t_check(rc == MT_OK && nlog == (int)n, "every directive parses", "%d of %d: %s", nlog,
                 (int)n, err.message))
        return;
    for (i = 0; i < n; ++i) {
        const seen *s = &log_[i];
        int k, nargs = strcmp(want[i].args, "16") == 0 ? 16 : (int)strlen(want[i].args);
        int ok = strcmp(s->directive, want[i].name) == 0 && s->nargs == nargs &&
                 s->nparams == want[i].nparams;
        for (k = 0; ok && k < nargs; ++k)
            ok = s->args[k].is_string == (nargs != 16 && want[i].args[k] == 's');
        if (!ok) {
            t_fail("directive arguments", "%s (statement %d): %d args, %d params", s->directive,
                   (int)i, s->nargs, s->nparams);
            all = 0;
        }
    }
    if (all) t_pass("every directive's argument shape");
    t_check(strcmp(log_[1].args[0].string, "StartTime") == 0 &&
                strcmp(log_[3].args[0].string, "All") == 0,
            "ActiveTransform keywords", "%s", log_[1].args[0].string);
    t_check(log_[14].args[0].number == 1 && log_[14].args[8].number == 9 &&
                log_[24].args[0].number == 90 && log_[33].args[12].number == 1 &&
                log_[33].args[14].number == 3 && log_[34].args[2].number == -3,
            "numeric arguments in order", "LookAt %g, Transform[12] %g",
            log_[14].args[0].number, log_[33].args[12].number);
    t_check(strcmp(log_[29].args[2].string, "checkerboard") == 0 &&
                strcmp(log_[29].args[1].string, "color") == 0,
            "Texture name, type, class", "%s", log_[29].args[2].string);
    for (i = 0; i < n; ++i)
        if (!mt_is_directive(want[i].name)) break;
    t_check(i == n && !mt_is_directive("texture") && !mt_is_directive("All") &&
                !mt_is_directive(NULL) && mt_is_directive("Include"),
            "mt_is_directive", "failed at %d", (int)i);
}

static void test_include(void)
{
    const char *dir = t_tmpdir_create("parser");
    char main_path[1024], sub[1100];
    mt_error err;
    mt_status rc;
    if (!dir) {
        t_fail("include: temp dir", "cannot create");
        return;
    }
    t_write_file("sub/a.pbrt", "Shape \"a\"\nInclude \"b.pbrt\"\n", (size_t)-1);
    t_write_file("sub/b.pbrt", "\n\nShape \"b\" \"string f\" \"x.exr\"", (size_t)-1);
    t_write_file("twice.pbrt", "Include \"sub/b.pbrt\" Include \"sub/b.pbrt\"", (size_t)-1);
    snprintf(main_path, sizeof main_path, "%s",
             t_write_file("main.pbrt", "WorldBegin\nInclude \"sub/a.pbrt\"\nWorldEnd\n", (size_t)-1));
    snprintf(sub, sizeof sub, "%s/sub", dir);
    reset_log();
    rc = mt_parse_file(main_path, NULL, record, NULL, &err);
    if (t_check(rc == MT_OK && nlog == 4, "include: nested files parse", "%d: %s", nlog,
                err.message)) {
        char out[1200] = "", want[1200];
        t_check(strcmp(log_[0].directive, "WorldBegin") == 0 &&
                    strcmp(log_[1].strs[0], "a") == 0 && strcmp(log_[2].strs[0], "b") == 0 &&
                    strcmp(log_[3].directive, "WorldEnd") == 0 && log_[3].line == 3 &&
                    strcmp(log_[3].file, main_path) == 0,
                "include: statements in order, back in the including file", "%s %s",
                log_[1].strs[0], log_[3].file);
        t_check(strstr(log_[2].file, "sub/b.pbrt") && log_[2].line == 3 &&
                    strcmp(log_[2].dir, sub) == 0,
                "include: relative to the including file (sub/b.pbrt from sub/a.pbrt)",
                "%s:%d dir %s", log_[2].file, log_[2].line, log_[2].dir);
        snprintf(want, sizeof want, "%s/x.exr", sub);
        mt_params_filename(log_[2].params, "f", "", out, sizeof out, &err);
        t_check(strcmp(out, want) == 0, "include: file names relative to the included file",
                "%s", out);
    }
    reset_log();
    rc = mt_parse_string("Include \"twice.pbrt\"", "<q>", dir, 1, NULL, record, NULL, &err);
    t_check(rc == MT_OK && nlog == 2, "include: the same file twice is no cycle; text's dir",
            "%d: %s", nlog, err.message);
    t_tmpdir_remove();
}

static void test_incomplete(void)
{
    static const struct {
        const char *text;
        int want;
    } cases[] = {
        {"Shape \"sphere\" \"float radius\" [", 1},
        {"Shape \"sphere\" \"float radius\" [ 1 2\n 3", 1},
        {"Shape \"sph", 1},
        {"Shape \"sphere\" \"float radius\" [1]", 0},
        {"Shape \"sphere\" # [ in a comment", 0},
        {"Texture \"a[\" \"float\"", 0},
        {"[ \"a]\"", 1},
        {"Shape \"x\\", 1},
        {"Shape \"a\\\n", 1},
        {"Shape \"a\nb\"", 0},
        {"", 0},
        {"]", 0},
        {"LookAt 0 0 0", 0},
        {"Shape @ [", 0},
    };
    size_t i;
    for (i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        char name[128];
        snprintf(name, sizeof name, "incomplete: case %d", (int)i);
        t_check(mt_parse_incomplete(cases[i].text) == cases[i].want, name, "\"%s\": want %d",
                cases[i].text, cases[i].want);
    }
    t_check(mt_parse_incomplete(NULL) == 0, "incomplete: NULL", "not 0");
}

static mt_status reject_second(void *ctx, const mt_statement *st, mt_error *err)
{
    int *count = ctx;
    if (++*count == 2) return mt_error_set(err, MT_ERR_UNSUPPORTED, "no %s here", st->directive);
    return MT_OK;
}

static void test_callback_error(void)
{
    mt_error err;
    int count = 0;
    mt_status rc = mt_parse_string("WorldBegin\n  Shape \"x\"\nWorldEnd", "cb.pbrt", NULL, 1, NULL,
                                   reject_second, &count, &err);
    t_check(rc == MT_ERR_UNSUPPORTED && count == 2 && strcmp(err.file, "cb.pbrt") == 0 &&
                err.line == 2 && err.column == 3 && strstr(err.message, "no Shape here"),
            "a callback error stops parsing, located at the statement", "%d %s:%d:%d %s", count,
            err.file, err.line, err.column, err.message);
}

static mt_status count_only(void *ctx, const mt_statement *st, mt_error *err)
{
    (*(long *)ctx)++;
    return MT_OK;
}

static void test_shared_scenes(void)
{
    static const char *const configs[] = {"bsdf-configs.txt", "texture-configs.txt"};
    const char *shared = t_shared_dir();
    char path[1024], dir[1024];
    struct dirent *e;
    DIR *d;
    int nscenes = 0;
    size_t i;
    if (!shared) {
        t_skip("shared scenes", "no shared reference data (../shared)");
        return;
    }
    /* every scene file of the reference data (one per material, the real
     * scenes) */
    snprintf(dir, sizeof dir, "%s/reference/scenes", shared);
    d = opendir(dir);
    while (d && (e = readdir(d)) != NULL) {
        size_t len = strlen(e->d_name);
        mt_error err;
        long n = 0;
        mt_status rc;
        char name[512];
        if (len < 6 || strcmp(e->d_name + len - 5, ".pbrt")) continue;
        nscenes++;
        if ((size_t)snprintf(path, sizeof path, "%s/%s", dir, e->d_name) >= sizeof path) continue;
        snprintf(name, sizeof name, "shared scene %.*s parses", (int)(len - 5), e->d_name);
        rc = mt_parse_file(path, NULL, count_only, &n, &err);
        t_check(rc == MT_OK && n > 10, name, "%ld statements: %s:%d:%d %s", n, err.file, err.line,
                err.column, err.message);
    }
    if (d) closedir(d);
    t_check(nscenes >= 17, "shared scenes: every material's and the real scenes", "%d scene files in %s",
            nscenes, dir);
    for (i = 0; i < 2; ++i) {
        FILE *f;
        char line[4096], name[128];
        int lines = 0, good = 0;
        snprintf(path, sizeof path, "%s/reference/pbrt-v2-values/%s", shared, configs[i]);
        f = fopen(path, "r");
        while (f && fgets(line, sizeof line, f)) {
            char *text = strrchr(line, '\t');
            mt_error err;
            long n = 0;
            if (!text) continue;
            lines++;
            if (mt_parse_string(text + 1, configs[i], dir, 1, NULL, count_only, &n, &err) == MT_OK &&
                n > 0)
                good++;
            else
                printf("# %s: %s\n", configs[i], err.message);
        }
        if (f) fclose(f);
        snprintf(name, sizeof name, "every line of %s parses", configs[i]);
        t_check(lines > 10 && good == lines, name, "%d of %d", good, lines);
    }
}

int main(void)
{
    test_strings();
    test_comments_numbers();
    test_locations();
    test_directives();
    test_include();
    test_incomplete();
    test_callback_error();
    test_shared_scenes();
    reset_log();
    return t_status();
}
