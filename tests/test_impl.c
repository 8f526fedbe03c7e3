/*
 * materia-conformance --impl, proven: materia's own query tool passes in both
 * modes, its pbrt-v2 errata expected failures (and the other precision's,
 * when make check names it in MATERIA_OTHER_QUERY), with the same rows as
 * materia run in the suite's own process (one conformance core); every
 * deliberately wrong implementation of tests/impl_wrong.c is caught by the
 * check meant to catch it, with the hostile ones (exit, crash, hang,
 * garbage, too few values, an extra line) reported as such, without hanging
 * the suite, and an erratum of pbrt-v2 made worse failed, not expected.
 *
 * And a renderer that is not pbrt-v2 (tests/impl_other.c: pbrt-v3's models
 * in float, radiance transport, two random numbers, one-lobe Fresnel glass,
 * a rough dielectric of its own in tests/impl_other.catalog) passes every
 * physics check with --compare none, its unsupported materials skipped,
 * while the agreement checks tell its models from pbrt-v2's; each of three
 * real bugs planted in it fails a physics row, the near-normal one at the
 * one incoming direction that shows it, with a reproducer that fails again
 * alone; declaring the wrong transport fails physics too. Runs the reduced
 * set (--quick) and, for the wrong ones, one configuration each.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "support/toutput.h"

static char bin[1100], tests_dir[1024], src_dir[1100];
static int failures;

/* cmd must exit with status `want`; each of the rows "VERDICT|text|text..."
 * must be present, and none of the lines `absent` holds; the output is
 * kept in *keep when keep is not NULL. */
static void expect_out(const char *name, const char *args, int want, const char *const *rows, const char *const *absent,
                       char **keep)
{
    char cmd[12000], *out = NULL;
    int st, ok, i;
    snprintf(cmd, sizeof cmd, "%.1100s/materia-conformance %.8192s 2>&1", bin, args);
    st = t_run_output(cmd, &out);
    ok = st == want && t_has_rows(out, rows);
    if (ok && want == 0 && !strstr(out, " passed, 0 failed")) ok = 0;
    for (i = 0; ok && absent && absent[i]; ++i)
        if (out && strstr(out, absent[i])) {
            ok = 0;
            printf("    holds \"%s\"\n", absent[i]);
        }
    printf("%s impl: %s (exit %d, want %d)\n", ok ? "PASS" : "FAIL", name, st, want);
    if (!ok) {
        failures++;
        printf("    command: %s\n", cmd);
        t_show_unpassed(out, 12);
    }
    if (keep)
        *keep = out;
    else
        free(out);
}

static void expect(const char *name, const char *args, int want, const char *const *rows)
{
    expect_out(name, args, want, rows, NULL, NULL);
}

/* The command the reproducer at the start of `line` ("      repro: FILE;
 * alone: COMMAND") gives, run from bin: its exit status, its output. */
static int rerun(const char *out, const char *marker, char **rout)
{
    const char *l = out ? strstr(out, marker) : NULL, *a, *e;
    char cmd[12000];
    *rout = NULL;
    if (!l || !(a = strstr(l, "; alone: materia-conformance "))) return -1;
    a += strlen("; alone: materia-conformance ");
    e = strchr(a, '\n');
    snprintf(cmd, sizeof cmd, "%.1100s/materia-conformance %.*s 2>&1", bin, (int)(e ? e - a : (long)strlen(a)), a);
    return t_run_output(cmd, rout);
}

/* impl-other BUG with --compare none on the configurations only selects:
 * a physics row must fail. */
static void other_bug(const char *bug, const char *only, const char *const *rows, char **keep, const char *extra)
{
    char args[8192], name[160];
    snprintf(args, sizeof args,
             "--impl '%.1000s/impl-other %.100s' --compare none --quick --catalog builtin --catalog '%.1000s/tests/impl_other.catalog' "
             "--only '%.200s' --threads 2 %.300s",
             tests_dir, bug, src_dir, only, extra);
    snprintf(name, sizeof name, "impl-other %s: a real bug, caught by physics alone", bug);
    expect_out(name, args, 1, rows, NULL, keep);
}

static void wrong(const char *bug, const char *only, const char *extra, const char *const *rows)
{
    char args[8192], name[128];
    snprintf(args, sizeof args, "--impl '%.1000s/impl-wrong %.100s' --quick --only '%.200s' --threads 2 %.200s", tests_dir, bug, only,
             extra);
    snprintf(name, sizeof name, "impl-wrong %s is caught", bug);
    expect(name, args, 1, rows);
}

int main(int argc, char **argv)
{
    char args[8192];
    const char *other = getenv("MATERIA_OTHER_QUERY");
    char *slash;
    (void)argc;
    snprintf(tests_dir, sizeof tests_dir, "%.1000s", argv[0]);
    slash = strrchr(tests_dir, '/');
    if (slash)
        *slash = 0;
    else
        snprintf(tests_dir, sizeof tests_dir, ".");
    snprintf(bin, sizeof bin, "%.1000s/../bin", tests_dir);
    /* the source tree (make check runs from it) */
    snprintf(src_dir, sizeof src_dir, ".");

    /* materia itself, both modes; and in this process, with the same rows */
    {
        char *child = NULL, *self = NULL;
        snprintf(args, sizeof args, "--impl '%s/materia-query' --quick --threads 2", bin);
        expect_out("materia-query passes, corrected mode", args, 0, NULL, NULL, &child);
        expect_out("materia in this process passes, corrected mode", "--impl-inprocess --quick --threads 2", 0, NULL, NULL,
                   &self);
        /* float: the same rows, value for value; double: the same verdicts
         * (t_same_runs says why) */
        if (t_same_runs(self, child))
            printf("PASS impl: in this process and through materia-query, the same rows (verdicts in double)\n");
        else {
            failures++;
            printf("FAIL impl: in this process and through materia-query, the same rows (verdicts in double): they differ\n");
        }
        free(child);
        free(self);
    }
    snprintf(args, sizeof args, "--impl '%s/materia-query' --quick --threads 2 --mode pbrt-v2", bin);
    {
        /* pbrt-v2's glossy-sample-pdf erratum, reproduced: expected failures */
        static const char *const same[] = {"XFAIL|plastic default|identity|the same way",
                                           "XFAIL|plastic default|chi2 materia|the same way",
                                           "XFAIL|plastic default|pdf integral|the same way", NULL};
        expect("materia-query passes, pbrt-v2 mode, pbrt-v2's failures expected", args, 0, same);
    }
    /* Snell's index of a refraction, oriented by the shading normal about
     * which the BSDF refracts: with ng tilted 37 degrees from it, a wo above
     * ns and below ng enters the glass (taken by ng, its index was 1/1.5) */
    snprintf(args, sizeof args,
             "--impl '%s/materia-query' --compare none --only '^glass ng tilted 37 deg$' --check helmholtz --quick --threads 2",
             bin);
    {
        static const char *const ns[] = {"PASS|glass ng tilted 37 deg|helmholtz|physics|index 1.5 by Snell", NULL};
        expect("helmholtz takes the side of a refraction from the shading normal", args, 0, ns);
    }
    if (other && *other && access(other, X_OK) == 0) {
        snprintf(args, sizeof args, "--impl '%.2000s' --quick --threads 2", other);
        expect("the other precision's materia-query passes", args, 0, NULL);
    } else {
        printf("SKIP impl: the other precision's materia-query (MATERIA_OTHER_QUERY not set: make check sets it)\n");
    }
    /* a renderer that is not pbrt-v2, honest: physics passes, its missing
     * materials skipped, agreement tells its models apart */
    {
        static const char *const clean[] = {"SKIP|translucent default|unsupported", "PASS|plastic roughness=0.001|chi2 ",
                                            "PASS|glass default|helmholtz|radiance",
                                            "PASS|roughglass index=1.5 roughness=0.01|reciprocity|index 1.5",
                                            "PASS|glass default|furnace  |radiance", NULL};
        static const char *const no_agreement[] = {"agree f", "chi2 materia", NULL};
        static const char *const differ[] = {"FAIL|plastic default|agree f|agreement", NULL};
        char *out = NULL;
        snprintf(args, sizeof args,
                 "--impl '%.1000s/impl-other' --compare none --quick --catalog builtin --catalog '%s/tests/impl_other.catalog' "
                 "--threads 2",
                 tests_dir, src_dir);
        expect_out("impl-other (pbrt-v3's models, radiance, two numbers) passes physics, --compare none", args, 0, clean,
                   no_agreement, NULL);
        snprintf(args, sizeof args, "--impl '%.1000s/impl-other' --quick --only '^(plastic default|glass default)$' --threads 2",
                 tests_dir);
        expect_out("impl-other compared with materia: its models differ (agreement), its physics holds", args, 1, differ,
                   NULL, &out);
        if (!out || !strstr(out, "physics: ") || !strstr(strstr(out, "physics: "), " 0 failed,")) {
            failures++;
            printf("FAIL impl: impl-other compared with materia fails no physics row\n");
        } else {
            printf("PASS impl: impl-other compared with materia fails no physics row\n");
        }
        free(out);
        /* materia (three numbers: u2 drives its glossy lobes) said to take two:
         * with u2 held at 1/2 its samples collapse */
        snprintf(args, sizeof args, "--impl '%s/materia-query' --compare none --quick --sample-numbers 2 --only '^plastic default$' --threads 2",
                 bin);
        {
            static const char *const two[] = {"FAIL|plastic default|chi2  |physics", NULL};
            expect("materia-query declared with two sample numbers fails chi2", args, 1, two);
        }
        /* its transport declared wrong: physics sees it, in the quick set too
         * (cos -0.9999 refracts out of glass of index 1.5: its furnace from
         * inside is 1.5^2 (1 - F) + F = 2.2, not 1) */
        snprintf(args, sizeof args, "--impl '%.1000s/impl-other' --compare none --quick --transport importance --only '^glass default$' --threads 2",
                 tests_dir);
        {
            static const char *const lie[] = {"FAIL|glass default|helmholtz|physics",
                                              "FAIL|glass default|furnace  |physics|rho 2.2", NULL};
            expect("impl-other declared with the wrong transport fails physics", args, 1, lie);
        }
    }
    /* its real bugs, planted one at a time */
    {
        static const char *const nearnormal[] = {"FAIL|plastic roughness=0.001|chi2  |physics", NULL};
        static const char *const facing[] = {"FAIL|roughglass index=1.5 roughness=0.01|pdf integral|physics", NULL};
        static const char *const negative[] = {"FAIL|substrate default|extremes|physics", NULL};
        char *out = NULL, *again = NULL, rp[1200];
        int st;
        snprintf(rp, sizeof rp, "--repro '%.1000s/impl-other-repro'", tests_dir);
        other_bug("nearnormal", "^plastic roughness=0.001$", nearnormal, &out, rp);
        /* the direction that shows it, named: cos theta 0.9999 at phi 40 degrees */
        if (out && strstr(out, "at wo (0.0108162314, 0.00911038648, 0.999899983), theta 0.8103 deg, phi 40.11 deg"))
            printf("PASS impl: the near-normal bug's row names its direction\n");
        else {
            failures++;
            printf("FAIL impl: the near-normal bug's row names its direction\n");
        }
        st = rerun(out, "repro: ", &again);
        if (st == 1 && again && t_has_row(again, "FAIL", "plastic roughness=0.001|chi2  |physics"))
            printf("PASS impl: the near-normal bug's reproducer fails alone\n");
        else {
            failures++;
            printf("FAIL impl: the near-normal bug's reproducer fails alone (exit %d)\n", st);
            t_show_unpassed(again, 6);
        }
        free(out);
        free(again);
        other_bug("facing", "^roughglass index=1.5 roughness=0.01$", facing, NULL, "");
        other_bug("blend-negative", "^substrate default$", negative, NULL, "");
    }
    /* the wrong ones, each caught where it should be */
    {
        static const char *const pdf[] = {"FAIL|pdf integral", "FAIL|agree pdf", NULL};
        static const char *const gain[] = {"FAIL|furnace  ", "FAIL|agree f", NULL};
        static const char *const recip[] = {"FAIL|reciprocity", NULL};
        static const char *const other_dir[] = {"FAIL|identity", NULL};
        static const char *const nan[] = {"FAIL|extremes", NULL};
        static const char *const colour[] = {"FAIL|agree f", "PASS|identity", "PASS|chi2  ", "PASS|furnace  ",
                                             "PASS|reciprocity", NULL};
        static const char *const skewed[] = {"FAIL|chi2  ", "FAIL|chi2 materia", "PASS|identity", NULL};
        /* pbrt-v2's erratum made worse: not expected failures (the previous
         * rule, "materia fails it too", made these three rows XFAIL) */
        static const char *const worse[] = {"FAIL|identity|worse than pbrt-v2 does",
                                             "FAIL|chi2  |not distributed as materia's",
                                             "FAIL|chi2 materia|not distributed as materia's",
                                             "XFAIL|pdf integral|the same way", "PASS|agree f", "PASS|agree pdf", NULL};
        static const char *const gone[] = {"FAIL|exited with status 3", NULL};
        static const char *const crash[] = {"FAIL|it crashed", NULL};
        static const char *const hang[] = {"FAIL|hung: no answer within 1 s", NULL};
        static const char *const garbage[] = {"FAIL|answered garbage", NULL};
        static const char *const few[] = {"FAIL|answered too few values (3 of 4)", NULL};
        static const char *const extra[] = {"FAIL|out of step", NULL};
        wrong("pdf-high", "^matte Kd=1$", "", pdf);
        wrong("energy-gain", "^matte Kd=1$", "", gain);
        wrong("nonreciprocal", "^plastic default$", "", recip);
        wrong("other-dir", "^plastic default$", "", other_dir);
        wrong("nan-grazing", "^matte Kd=1$", "", nan);
        wrong("colour", "^plastic default$", "", colour);
        wrong("skewed", "^plastic default$", "", skewed);
        wrong("glossy-below", "^plastic default$", "--mode pbrt-v2", worse);
        wrong("exit", "^plastic default$", "", gone);
        wrong("crash", "^plastic default$", "", crash);
        wrong("hang", "^plastic default$", "--timeout 1", hang);
        wrong("garbage", "^plastic default$", "", garbage);
        wrong("few", "^plastic default$", "", few);
        wrong("extra", "^plastic default$", "", extra);
    }
    return failures ? 1 : 0;
}
