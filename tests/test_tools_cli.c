/*
 * What a user meets on the command line of every tool: --help on standard
 * output with status 0, --version naming materia's version, a wrong option
 * with status 2 (0 success, 1 failure, 2 usage throughout); materia-render's
 * output path checked before it renders (a missing directory, an unknown
 * extension), a bad material parameter failing with nothing written,
 * --quiet dropping the Sampler notice, no progress line (no carriage return)
 * when standard error is a file; materia-query's warnings for parameters a
 * statement did not use; materia-conformance's --only that selects nothing,
 * and --impl's command line (--impl --help, and each mistake a usage error
 * naming the option before anything runs); an option given last without its
 * value named as such (not as unknown), a --dir that is not a directory,
 * output paths checked before the work and nothing half-written
 * (materia-sheet, materia-golden); the detection-curve scripts' --help
 * and usage errors (tradeoff/8-detection.sh, mitsuba_detection.py).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "support/check.h"
#include "support/tfiles.h"
#include "support/toutput.h"
#include "support/ttools.h"

static const char *const tools[] = {"materia-render", "materia-query", "materia-imgdiff",
                                    "materia-sheet",  "materia-merl",  "materia-conformance",
                                    "materia-lobe",   "materia-golden"};

static void every_tool(void)
{
    char name[160], want[64];
    size_t i;
    snprintf(want, sizeof want, "(materia) %s, %s", MT_VERSION, mt_precision());
    for (i = 0; i < sizeof tools / sizeof tools[0]; ++i) {
        snprintf(name, sizeof name, "%s --help: usage on standard output, status 0", tools[i]);
        t_tool_check(name, tools[i], "--help", 0, "out.txt", "usage: ");
        snprintf(name, sizeof name, "%s --version: \"%s\", status 0", tools[i], want);
        t_tool_check(name, tools[i], "--version", 0, "out.txt", want);
        snprintf(name, sizeof name, "%s --no-such-option: status 2, named on standard error", tools[i]);
        t_tool_check(name, tools[i], "--no-such-option", 2, "err.txt", "--no-such-option");
    }
}

static const char *bindir; /* BUILD/bin */

static int exists(const char *name) { return access(t_tmp_path(name), F_OK) == 0; }

/* The whole of a file of the source tree (the tests run from it), or NULL. */
static char *slurp(const char *path)
{
    FILE *f = fopen(path, "rb");
    char *s = NULL;
    long n;
    if (f && fseek(f, 0, SEEK_END) == 0 && (n = ftell(f)) >= 0 && fseek(f, 0, SEEK_SET) == 0 &&
        (s = calloc(1, (size_t)n + 1)) != NULL && fread(s, 1, (size_t)n, f) != (size_t)n) {
        free(s);
        s = NULL;
    }
    if (f) fclose(f);
    return s;
}

/* --help names every option the tool's source compares an argument with
 * ("--spp", "-o": a string literal of a dash and letters), each at the start
 * of a line of its own explanation, and the exit statuses; for the tools a
 * newcomer meets first, every option's explanation gives its default (or
 * says it is required). */
static void help_lists_every_option(void)
{
    static const struct {
        const char *tool, *args, *src;
        int defaults;
    } t[] = {{"materia-render", "--help", "tools/materia-render.c", 1},
             {"materia-lobe", "--help", "tools/materia-lobe.c", 1},
             {"materia-golden", "--help", "tools/materia-golden.c", 1},
             {"materia-imgdiff", "--help", "tools/materia-imgdiff.c", 1},
             {"materia-merl", "--help", "tools/materia-merl.c", 1},
             {"materia-query", "--help", "tools/materia-query.c", 1},
             {"materia-sheet", "--help", "tools/materia-sheet.c", 1},
             {"materia-conformance", "--help", "conformance/main.c", 1},
             {"materia-conformance", "--impl --help", "conformance/impl_main.c", 1}};
    size_t i;
    for (i = 0; i < sizeof t / sizeof t[0]; ++i) {
        char *src = slurp(t[i].src), *help, *p, missing[512] = "", name[160];
        size_t m = 0;
        t_tool_run(t[i].tool, t[i].args);
        help = slurp(t_tmp_path("out.txt"));
        for (p = src; p && (p = strstr(p, "\"-")) != NULL; ++p) {
            char opt[40], line[48], *at, *next;
            size_t n = strspn(p + 1, "-abcdefghijklmnopqrstuvwxyz0123456789");
            if (n < 2 || n >= sizeof opt || p[1 + n] != '"' || p[n] == '-') continue; /* "--" itself, or a prefix */
            memcpy(opt, p + 1, n);
            opt[n] = 0;
            /* an explanation: the option first on a line (after spaces or ", ") */
            snprintf(line, sizeof line, "  %s ", opt);
            at = help ? strstr(help, line) : NULL;
            if (!at) snprintf(line, sizeof line, ", %s ", opt), at = help ? strstr(help, line) : NULL;
            if (!at) snprintf(line, sizeof line, "  %s,", opt), at = help ? strstr(help, line) : NULL;
            if (!at) snprintf(line, sizeof line, "  %s\n", opt), at = help ? strstr(help, line) : NULL;
            next = at ? strstr(at + strlen(line), "\n  -") : NULL;
            if (at && t[i].defaults && strcmp(opt, "--help") && strcmp(opt, "-h") && strcmp(opt, "--version")) {
                /* its default or that it is required, before the next option */
                char *d = strstr(at, "default"), *r = strstr(at, "required"), *e = strstr(at, "instead");
                if (!((d && (!next || d < next)) || (r && (!next || r < next)) || (e && (!next || e < next))))
                    at = NULL;
            }
            if (!at && !strstr(missing, opt) && m + n + 2 < sizeof missing)
                m += (size_t)snprintf(missing + m, sizeof missing - m, " %s", opt);
        }
        snprintf(name, sizeof name, "%s %s: every option explained%s, and the exit statuses", t[i].tool,
                 t[i].args, t[i].defaults ? " with its default" : "");
        t_check(src && help && !missing[0] && strstr(help, "Exit status"), name, "%s",
                !src ? "source not found (run from the source tree)"
                     : missing[0] ? missing : "no \"Exit status\" paragraph");
        free(src);
        free(help);
    }
}

static const char scene[] = "Film \"image\" \"integer xresolution\" [8] \"integer yresolution\" [6]\n"
                            "Sampler \"lowdiscrepancy\" \"integer pixelsamples\" [1]\n"
                            "Camera \"perspective\"\n"
                            "WorldBegin\n"
                            "LightSource \"distant\"\n"
                            "Translate 0 0 5\n"
                            "Material \"plastic\" \"float roughness\" [%s]\n"
                            "Shape \"sphere\"\n"
                            "WorldEnd\n";

static void render(void)
{
    char text[1024];
    snprintf(text, sizeof text, scene, "0.1");
    t_write_file("good.pbrt", text, (size_t)-1);
    snprintf(text, sizeof text, scene, "-0.1");
    t_write_file("bad.pbrt", text, (size_t)-1);
    if (!t_has_format("exr", "render: the checks that write EXR images")) return;
    t_tool_check("render: writes the image", "materia-render", "good.pbrt -o good.exr", 0, "err.txt", "");
    t_check(exists("good.exr"), "render: good.exr exists", "not written");
    t_check(t_file_holds("err.txt", "warning: Sampler \"lowdiscrepancy\""), "render: the Sampler notice without --quiet",
            "err.txt lacks it");
    t_check(!t_file_holds("err.txt", "\r") && !t_file_holds("err.txt", "rendering:"),
            "render: no progress line when standard error is a file", "err.txt has one");
    t_tool_check("render: --quiet drops the Sampler notice", "materia-render", "--quiet good.pbrt -o quiet.exr", 0,
                 "err.txt", "");
    t_check(!t_file_holds("err.txt", "Sampler") && !t_file_holds("err.txt", "spp"), "render: --quiet is quiet",
            "err.txt is not empty");
    t_tool_check("render: an output in a missing directory fails before the render", "materia-render",
                 "good.pbrt -o nosuchdir/x.exr", 1, "err.txt", "nosuchdir/x.exr: no directory \"nosuchdir\"");
    t_tool_check("render: an unknown extension fails before the render", "materia-render", "good.pbrt -o x.tiff", 1,
                 "err.txt", "x.tiff: unknown image type");
    t_check(!exists("x.tiff"), "render: nothing written for x.tiff", "x.tiff exists");
    t_tool_check("render: a bad --variance path fails before the render", "materia-render",
                 "good.pbrt -o v.exr --variance nosuchdir/v.exr", 1, "err.txt", "no directory");
    t_check(!exists("v.exr"), "render: nothing written when --variance is bad", "v.exr exists");
    t_tool_check("render: a negative roughness is an error at its line, status 1", "materia-render",
                 "bad.pbrt -o bad.exr", 1, "err.txt", "bad.pbrt:7:20: parameter \"roughness\": plastic material");
    t_check(!exists("bad.exr"), "render: nothing written for a bad material", "bad.exr exists");
    t_tool_check("render: a missing scene file is status 1", "materia-render", "missing.pbrt", 1, "err.txt",
                 "missing.pbrt");
    t_tool_check("render: no scene is status 2", "materia-render", "", 2, "err.txt", "usage");
    t_tool_check("render: a bad --spp is status 2", "materia-render", "good.pbrt --spp 0", 2, "err.txt", "--spp");
}

static void query(void)
{
    t_write_file("q.txt",
                 "Material \"matte\" \"rgb Kdd\" [0.3 0.3 0.3] \"float roughness\" [0.2]\n"
                 "Texture \"t\" \"float\" \"fbm\" \"integer octave\" [3]\n"
                 "Material \"plastic\" \"float roughness\" [0.2]\n"
                 "Material \"plastic\" \"float roughness\" [-1]\n",
                 (size_t)-1);
    t_tool_check("query: statements with unused parameters are answered ok", "materia-query", "< q.txt", 0,
                 "out.txt", "ok\nok\nok\nerror <input>:4:20: parameter \"roughness\"");
    t_check(t_file_holds("err.txt", "warning <input>:1: Parameter \"roughness\" not used\n") &&
                t_file_holds("err.txt", "warning <input>:1: Parameter \"Kdd\" not used\n") &&
                t_file_holds("err.txt", "warning <input>:2: Parameter \"octave\" not used\n") &&
                !t_file_holds("err.txt", "<input>:3:"),
            "query: a warning on standard error for each unused parameter, none for a used one",
            "standard error differs");
    t_tool_check("query: --dir without a directory is status 2", "materia-query", "--dir", 2, "err.txt", "--dir");
}

static void conformance(void)
{
    /* --impl's command line: every mistake is a usage error (status 2) that
     * names the option, found before any configuration runs (the command
     * "q" does not exist: running it would fail otherwise) */
    static const char *const usage_errors[][3] = {
        {"--impl without a value", "--impl", "--impl needs a value"},
        {"--impl ''", "--impl ''", "--impl needs a command"},
        {"--impl of blanks", "--impl '  '", "--impl needs a command"},
        {"an option where --impl's value is expected", "--impl --quick", "--impl needs a value (got the option \"--quick\")"},
        {"--mode without a value", "--impl q --mode", "--mode needs a value"},
        {"an unknown mode", "--impl q --mode pbrt-v3", "--mode: \"pbrt-v3\""},
        {"--samples below 100", "--impl q --samples 10", "--samples: \"10\""},
        {"--samples negative", "--impl q --samples -5", "--samples: \"-5\""},
        {"--cells beyond int", "--impl q --cells 4294967300", "--cells: \"4294967300\""},
        {"--threads 0", "--impl q --threads 0", "--threads: \"0\""},
        {"--timeout nan", "--impl q --timeout nan", "--timeout: \"nan\""},
        {"--timeout empty", "--impl q --timeout ''", "--timeout: \"\""},
        {"an unknown option", "--impl q --frobnicate", "unknown argument \"--frobnicate\""},
        {"a stray word", "--impl q stray", "unknown argument \"stray\""},
        {"--impl twice", "--impl q --impl r", "--impl is given twice"},
        {"--only not a regular expression", "--impl q --only '('", "--only: \"(\""},
        {"--only selecting nothing", "--impl q --only 'no such configuration' --plots pl", "selects no configuration"},
        {"--report in a missing directory", "--impl q --report nosuchdir/r.json", "--report: cannot write \"nosuchdir/r.json\""},
        {"--plots-all without --plots", "--impl q --plots-all", "--plots-all needs --plots"},
        {"an unknown --compare", "--impl q --compare pbrt", "--compare: \"pbrt\""},
        {"an unknown --check", "--impl q --check chi3", "--check: \"chi3\""},
        {"an unknown --transport", "--impl q --transport adjoint", "--transport: \"adjoint\""},
        {"--sample-numbers 4", "--impl q --sample-numbers 4", "--sample-numbers: \"4\""},
        {"--significance 1", "--impl q --significance 1", "--significance: \"1\""},
        {"--wo negative", "--impl q --wo -1", "--wo: \"-1\""},
        {"--impl with --impl-inprocess", "--impl q --impl-inprocess", "--impl and --impl-inprocess name two"},
        {"a --catalog that does not exist", "--impl q --catalog no-such-catalog.txt", "no-such-catalog.txt:"},
    };
    size_t i;
    t_tool_check("conformance: --only that selects nothing is status 2", "materia-conformance",
                 "--only no-such-configuration", 2, "err.txt", "selects no configuration");
    t_tool_check("conformance: a bad --threads is status 2", "materia-conformance", "--threads x", 2, "err.txt",
                 "--threads");
    t_tool_check("conformance: --impl --help is --impl's usage on standard output, status 0", "materia-conformance",
                 "--impl --help", 0, "out.txt", "--impl 'COMMAND' [--mode pbrt-v2|corrected]");
    t_check(t_file_holds("out.txt", "--timeout S") && !t_file_holds("out.txt", "FAIL"),
            "conformance: --impl --help runs nothing", "out.txt lacks the options or holds a verdict");
    for (i = 0; i < sizeof usage_errors / sizeof usage_errors[0]; ++i) {
        char name[160];
        snprintf(name, sizeof name, "conformance: %s is a usage error naming it", usage_errors[i][0]);
        t_tool_check(name, "materia-conformance", usage_errors[i][1], 2, "err.txt", usage_errors[i][2]);
    }
    t_check(!exists("pl"), "conformance: no --plots directory made for a usage error", "pl exists");
}

/* An option that takes a value, given last: "OPTION needs a value", status 2. */
static void no_value(void)
{
    static const char *const cases[][2] = {
        {"materia-render", "good.pbrt -o"},        {"materia-render", "good.pbrt --spp"},
        {"materia-query", "--dir"},                {"materia-imgdiff", "a.exr b.exr --block"},
        {"materia-imgdiff", "a.exr b.exr --heatmap"}, {"materia-sheet", "good.exr -o"},
        {"materia-sheet", "-o s.png good.exr --columns"}, {"materia-merl", "--out"},
        {"materia-merl", "--out m.binary --dir"},  {"materia-lobe", "--wo 30 0 -o l.png --samples"},
        {"materia-golden", "good.pbrt -o"},
        {"materia-golden", "good.pbrt --points"}};
    size_t i;
    for (i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        const char *opt = strrchr(cases[i][1], ' ') ? strrchr(cases[i][1], ' ') + 1 : cases[i][1];
        char name[200], want[64];
        snprintf(name, sizeof name, "%s %s: \"%s needs a value\", status 2", cases[i][0], cases[i][1], opt);
        snprintf(want, sizeof want, "%s needs a value", opt);
        t_tool_check(name, cases[i][0], cases[i][1], 2, "err.txt", want);
    }
    t_tool_check("lobe: --wo with one value is status 2, saying it needs two", "materia-lobe", "-o l.png --wo 30", 2,
                 "err.txt", "--wo needs two values");
    t_tool_check("imgdiff: an unknown option given last is unknown, status 2", "materia-imgdiff",
                 "a.exr b.exr --bogus", 2, "err.txt", "unknown option --bogus");
    t_tool_check("sheet: an unknown option given last is unknown, status 2", "materia-sheet", "-o s.png --bogus", 2,
                 "err.txt", "unknown option --bogus");
}

/* One dialect for every --only: POSIX extended regular expressions. A
 * lookahead (a Python construct examples once used) is a usage error
 * naming the option for materia-conformance --impl and for vectors/check.py
 * alike, and what replaces it there (--only with --skip) selects the same
 * configurations (the documented twelve of the example). */
static void only_dialect(void)
{
    char cmd[512], *out = NULL;
    int rc;
    t_tool_check("conformance --impl: a lookahead in --only is a usage error (POSIX ERE)", "materia-conformance",
                 "--impl q --only '^plastic (?!.*bump)'", 2, "err.txt", "is not a regular expression");
    if (t_run_output("python3 -c 'import sys; sys.exit(sys.version_info < (3, 6))' 2>/dev/null", &out) != 0) {
        free(out);
        t_skip("check.py --only", "python3 (3.6 or later) is not installed");
        return;
    }
    free(out);
    snprintf(cmd, sizeof cmd, "python3 vectors/check.py --impl true --only '^plastic (?!.*bump)' 2>&1");
    rc = t_run_output(cmd, &out);
    t_check(rc == 2 && out && strstr(out, "--only") && strstr(out, "POSIX extended"),
            "check.py: a lookahead in --only is a usage error (POSIX ERE)", "status %d: %s", rc, out ? out : "");
    free(out);
    /* what replaces the lookahead: the example's twelve configurations */
    snprintf(cmd, sizeof cmd,
             "python3 vectors/check.py --impl '%s/materia-query' --only '^(matte|plastic|mirror) ' "
             "--skip 'textured|bump' --files eval 2>&1", bindir);
    rc = t_run_output(cmd, &out);
    t_check(rc == 0 && out && strstr(out, "(12 configurations"),
            "check.py: --only '^(matte|plastic|mirror) ' --skip 'textured|bump' selects the 12 the example names",
            "status %d: %s", rc, out ? out : "");
    free(out);
}

static void others(void)
{
    int png = t_has_format("png", "sheet and lobe: the checks of their PNG outputs' paths");
    t_tool_check("imgdiff: a missing image is status 1", "materia-imgdiff", "a.exr b.exr", 1, "err.txt", "a.exr");
    if (png)
        t_tool_check("sheet: a heat map in a missing directory fails before the work", "materia-sheet",
                     "-o nosuchdir/s.png good.exr", 1, "err.txt", "no directory");
    t_tool_check("merl: no --out is status 2", "materia-merl", "'Material \"matte\"'", 2, "err.txt", "--out");
    static const struct {
        const char *name, *tool, *args;
        int status;
        const char *text; /* on standard error */
    } bad[] = {
        {"sheet: the output path is checked before any image is read", "materia-sheet",
         "-o nosuchdir/s.png missing.exr", 1, "nosuchdir/s.png: no directory"},
        {"sheet: LABEL= without an image is status 2", "materia-sheet", "-o s.png label=", 2,
         "\"label=\" names no image"},
        {"query: a --dir that does not exist is status 1, named", "materia-query", "--dir nosuchdir", 1,
         "--dir \"nosuchdir\": No such file or directory"},
        {"query: a --dir that is a file is status 1", "materia-query", "--dir good.pbrt", 1,
         "--dir \"good.pbrt\": not a directory"},
        {"merl: a --dir that does not exist is status 1, named", "materia-merl",
         "--out m.binary --dir nosuchdir 'Material \"matte\"'", 1, "--dir \"nosuchdir\""},
        {"merl: an unknown material is located at its statement", "materia-merl",
         "--out m.binary 'Texture \"t\" \"float\" \"constant\"' 'Material \"nosuch\"'", 1,
         "<statements>:2:1: material type \"nosuch\" unknown"},
        {"merl: a parameter out of range is located at its statement", "materia-merl",
         "--out m.binary 'Material \"plastic\" \"float roughness\" [-1]'", 1,
         "<statements>:1:20: parameter \"roughness\""}};
    size_t i;
    for (i = 0; i < sizeof bad / sizeof bad[0]; ++i)
        if (png || !strstr(bad[i].args, "nosuchdir/s.png"))
            t_tool_check(bad[i].name, bad[i].tool, bad[i].args, bad[i].status, "err.txt", bad[i].text);
    t_check(!exists("m.binary"), "merl: nothing written for a bad --dir or a bad material", "m.binary exists");
    t_tool_check("golden: --renders 1 is status 2, saying why", "materia-golden",
                 "good.pbrt --renders 1 --spp 1 -o m.exr --variance v.exr --stats s.txt", 2, "err.txt",
                 "--renders K needs K >= 2");
    t_tool_check("golden: a bad --variance path fails before the renders", "materia-golden",
                 "good.pbrt --renders 2 --spp 1 -o m.pfm --variance nosuchdir/v.pfm --stats s.txt", 1, "err.txt",
                 "nosuchdir/v.pfm: no directory");
    t_check(!t_file_holds("err.txt", "render 1 of") && !exists("m.pfm") && !exists("s.txt") &&
                !exists("s.txt.tmp"),
            "golden: nothing rendered or written for a bad --variance path", "a render ran or a file was left");
    if (png) {
        t_tool_check("lobe: an output in a missing directory fails before the measurement", "materia-lobe",
                     "--wo 30 0 -o nosuchdir/l.png --impl 'touch ran; cat' 'Material \"matte\"'", 1, "err.txt",
                     "nosuchdir/l.png: no directory");
        t_tool_check("lobe: a --raw prefix in a missing directory fails before the measurement", "materia-lobe",
                     "--wo 30 0 -o l.png --raw nosuchdir/x --impl 'touch ran; cat' 'Material \"matte\"'", 1, "err.txt",
                     "nosuchdir/x-A-fcos.pfm: no directory");
        t_check(!exists("ran") && !exists("l.png"), "lobe: no implementation started, nothing written for a bad path",
                "the implementation ran or l.png exists");
    }
    t_tool_check("golden: an unknown option is named, status 2", "materia-golden", "good.pbrt --bogus", 2, "err.txt",
                 "unknown option --bogus");
}

/* The detection-curve script (tradeoff/8-detection.sh, not run by make
 * check: tens of minutes) and its Mitsuba half: --help, and the mistakes
 * that stop them before any measurement. A few ms. */
static void detection_script(void)
{
    static const struct {
        const char *name, *cmd;
        int status;
        const char *text;
    } runs[] = {
        {"8-detection.sh --help: its usage, status 0", "sh tradeoff/8-detection.sh --help", 0, "DET_CURVES"},
        {"8-detection.sh without a build: status 1, saying what to set",
         "DET_BUILD= MT_BIN= OUT=. sh tradeoff/8-detection.sh", 1, "set DET_BUILD"},
        {"8-detection.sh with a build that lacks the programs: status 1, named",
         "DET_BUILD=nosuchdir OUT=. sh tradeoff/8-detection.sh", 1, "nosuchdir/bin/materia-conformance: not built"},
        {"mitsuba_detection.py --help: status 0", "python3 tradeoff/mitsuba_detection.py --help", 0, "usage:"},
        {"mitsuba_detection.py: an unknown configuration is status 2, named",
         "python3 tradeoff/mitsuba_detection.py x.so 'glass' warp 0.01 1", 2, "'glass': not one of"}};
    char cmd[512], *out = NULL;
    size_t i;
    int rc, py = t_run_output("python3 -c 'import sys; sys.exit(sys.version_info < (3, 6))' 2>/dev/null", &out) == 0;
    free(out);
    for (i = 0; i < sizeof runs / sizeof runs[0]; ++i) {
        if (!py && strstr(runs[i].cmd, "python3")) {
            t_skip(runs[i].name, "python3 (3.6 or later) is not installed");
            continue;
        }
        snprintf(cmd, sizeof cmd, "%s 2>&1", runs[i].cmd);
        out = NULL;
        rc = t_run_output(cmd, &out);
        t_check(rc == runs[i].status && out && strstr(out, runs[i].text), runs[i].name, "status %d: %s", rc,
                out ? out : "");
        free(out);
    }
}

int main(int argc, char **argv)
{
    (void)argc;
    bindir = t_tool_bindir(argv[0]);
    if (!t_tmpdir_create("tools")) {
        t_fail("tools", "cannot create a temporary directory");
        return t_status();
    }
    every_tool();
    help_lists_every_option();
    render();
    query();
    conformance();
    no_value();
    only_dialect();
    others();
    detection_script();
    t_tmpdir_remove();
    return t_status();
}
