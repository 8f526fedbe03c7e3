/*
 * The worked example (examples/pbrt_materials.py, an independent Python
 * implementation of matte, plastic, mirror and glass), as examples/README.md runs
 * it:
 *
 * - against the published vectors through vectors/check.py: it must pass in
 *   both modes, and each of its planted bugs (a pdf 5% high, a Fresnel term
 *   from the wrong side, a colour channel 3% low) must be caught;
 * - through materia-conformance --impl, at a smaller size than the README's
 *   (--quick with 200 samples per direction and 4 x 5 cells, which still
 *   catches each bug): in pbrt-v2 mode it passes, pbrt-v2's
 *   glossy-sample-pdf erratum reproduced as expected failures of plastic,
 *   and each planted bug fails the checks the README names while the
 *   others pass.
 *
 * Skipped when python3 is missing. Runs from the source tree (make check's
 * directory).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "support/check.h"
#include "support/toutput.h"
#include "support/ttools.h"

/* the vectors' configurations of these four materials that the example
 * implements (no textures, no bump maps) */
#define CONFIGS "'^(matte|plastic|mirror|glass) ' --skip 'textured|bump'"

/* vectors/check.py on the example: its exit status, its output in *out. */
static int check_py(const char *impl_args, const char *configs, const char *files, char **out)
{
    char cmd[1024];
    snprintf(cmd, sizeof cmd,
             "python3 vectors/check.py --impl 'python3 examples/pbrt_materials.py %s' --only %s --files %s 2>&1",
             impl_args, configs, files);
    return t_run_output(cmd, out);
}

static void vectors(void)
{
    static const char *bugs[] = {"pdf", "fresnel", "colour"};
    char *out;
    int rc, i;
    /* its PASS lines count as this test's */
    rc = check_py("", CONFIGS, "eval,sample", &out);
    if (out) fputs(out, stdout);
    free(out);
    t_check(rc == 0, "example: matte, plastic, mirror and glass agree with the vectors in both modes",
            "vectors/check.py exited %d", rc);
    for (i = 0; i < 3; ++i) {
        char args[64], name[96];
        snprintf(args, sizeof args, "--bug %s", bugs[i]);
        rc = check_py(args, "'^plastic default'", "eval", &out);
        snprintf(name, sizeof name, "example: the planted bug \"%s\" is caught", bugs[i]);
        /* plastic's default has all three components the bugs touch; its
         * FAIL lines are the expected outcome: not passed through */
        t_check(rc == 1 && out && strstr(out, "FAIL ") != NULL, name, "vectors/check.py exited %d:\n%s", rc,
                out ? out : "");
        free(out);
    }
}

/* Through materia-conformance --impl: the run, its exit status and the rows
 * ("VERDICT|configuration|check...") that examples/README.md says it prints. */
typedef struct impl_case {
    const char *bug, *mode, *only;
    int status;
    const char *rows[8];
} impl_case;

static const impl_case impl_cases[] = {
    {"", "pbrt-v2", "^(plastic default|mirror default)$", 0,
     {"XFAIL|plastic default|identity|the same way", "XFAIL|plastic default|chi2 materia|the same way",
      "XFAIL|plastic default|pdf integral|the same way", "PASS|plastic default|agree f", "PASS|plastic default|agree pdf",
      "PASS|mirror default|agree delta", NULL}},
    /* the Lambertian pdf 5% high, in eval and sample alike */
    {"pdf", "corrected", "^matte Kd=1$", 1,
     {"FAIL|pdf integral", "FAIL|furnace MC=quad", "FAIL|agree pdf", "PASS|identity", "PASS|agree f", NULL}},
    /* green 3% low: only a comparison with materia sees it */
    {"colour", "corrected", "^(matte Kd=1|mirror default)$", 1,
     {"FAIL|matte Kd=1|agree f", "FAIL|mirror default|agree delta", "PASS|matte Kd=1|identity",
      "PASS|matte Kd=1|chi2  ", "PASS|matte Kd=1|furnace  ", "PASS|matte Kd=1|reciprocity", NULL}},
    /* plastic's Fresnel term from the other side */
    {"fresnel", "corrected", "^plastic default$", 1,
     {"FAIL|agree f", "PASS|identity", "PASS|chi2  ", "PASS|furnace  ", "PASS|reciprocity", "PASS|agree pdf", NULL}},
};

static void through_impl(const char *bindir)
{
    size_t i;
    for (i = 0; i < sizeof impl_cases / sizeof impl_cases[0]; ++i) {
        const impl_case *c = &impl_cases[i];
        char cmd[2048], name[160];
        snprintf(cmd, sizeof cmd,
                 "'%s/materia-conformance' --impl 'python3 examples/pbrt_materials.py%s%s' --mode %s --only '%s' "
                 "--quick --samples 200 --cells 4 --threads 1 --timeout 60 2>&1",
                 bindir, c->bug[0] ? " --bug " : "", c->bug, c->mode, c->only);
        if (c->bug[0])
            snprintf(name, sizeof name, "example --impl: the planted bug \"%s\" fails the checks examples/README.md names",
                     c->bug);
        else
            snprintf(name, sizeof name, "example --impl: passes in %s mode, pbrt-v2's erratum an expected failure",
                     c->mode);
        t_check_run(name, cmd, c->status, c->rows, NULL);
    }
}

int main(int argc, char **argv)
{
    (void)argc;
    if (system("python3 -c 'import sys; sys.exit(sys.version_info < (3, 6))' >/dev/null 2>&1") != 0) {
        t_skip("example", "python3 (3.6 or later) is not installed: examples/pbrt_materials.py not run");
        return 0;
    }
    vectors();
    through_impl(t_tool_bindir(argv[0]));
    return t_status();
}
