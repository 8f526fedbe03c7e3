/*
 * Declared conventions, proven on the Python example
 * (examples/pbrt_materials.py): physics only (--compare none), each
 * convention passes when the implementation declares what it does, and a
 * physics row fails when it declares something else
 * (docs/TESTING-YOUR-RENDERER.md, section 7, shows these rows).
 *
 * - transport: importance (pbrt-v2's specular transmission) and radiance
 *   (pbrt-v3's, times (eta_i/eta_t)^2) each pass declared honestly; radiance
 *   declared as importance fails the furnace from inside the glass (2.25 times
 *   the transmitted light at index 1.5) and Helmholtz, importance declared as
 *   radiance fails the furnace from outside and Helmholtz's radiance form;
 * - sample numbers: 3 (pbrt-v2's) and 2 (pbrt-v3's rescaled uc) each pass
 *   declared honestly; 3 declared as 2 fails chi2 (the suite holds the unused
 *   u2 fixed, and its directions need it); 2 declared as 3 passes, rightly: a
 *   rescaled uc is uniform and independent of u1, so its samples are a
 *   correct sampler's.
 *
 * And the walkthrough's first step: examples/empty_adapter.py, the protocol
 * with no material, gets every configuration of the quick set skipped and a
 * clean exit.
 *
 * Two glass configurations with every incoming direction (light from inside
 * the glass is what tells the transports apart), or plastic and matte, at
 * 1000 samples and 4 x 5 cells: 8 runs of 1.5 to 4 s of CPU each (22 s of
 * CPU in all, measured; 70 s wall on 2 loaded cores), and the empty adapter's
 * 0.5 s. Skipped when python3 is missing. Runs from the source tree.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "support/check.h"
#include "support/toutput.h"
#include "support/ttools.h"

#define GLASS "^glass (default|coloured Kr Kt)$"
#define PLASTIC "^(plastic default|matte Kd=1)$"

typedef struct conv_case {
    const char *name, *flags, *only;
    int status;
    const char *rows[6];
} conv_case;

static const conv_case cases[] = {
    {"importance declared importance", "--transport importance", GLASS, 0,
     {"PASS|glass default|furnace  ", "PASS|glass default|helmholtz", "PASS|glass coloured Kr Kt|furnace  ", NULL}},
    {"radiance declared radiance", "--transport radiance", GLASS, 0,
     {"PASS|glass default|furnace  ", "PASS|glass default|helmholtz", "PASS|glass coloured Kr Kt|furnace  ", NULL}},
    {"radiance declared importance", "--transport radiance --declare-transport importance", GLASS, 1,
     {"FAIL|glass default|furnace  |rho 2.200000 at cos -1", "FAIL|glass default|helmholtz|(importance)",
      "FAIL|glass coloured Kr Kt|furnace  ", NULL}},
    {"importance declared radiance", "--transport importance --declare-transport radiance", GLASS, 1,
     {"FAIL|glass default|furnace  |radiance: light from wo", "FAIL|glass default|helmholtz|(radiance)",
      "FAIL|glass coloured Kr Kt|helmholtz", NULL}},
    {"3 numbers declared 3", "--sample-numbers 3", PLASTIC, 0, {"PASS|plastic default|chi2  ", NULL}},
    {"2 numbers declared 2", "--sample-numbers 2", PLASTIC, 0, {"PASS|plastic default|chi2  ", NULL}},
    {"3 numbers declared 2", "--sample-numbers 3 --declare-sample-numbers 2", PLASTIC, 1,
     {"FAIL|plastic default|chi2  ", "FAIL|matte Kd=1|chi2  ", NULL}},
    {"2 numbers declared 3 (a correct sampler all the same)", "--sample-numbers 2 --declare-sample-numbers 3",
     PLASTIC, 0, {"PASS|plastic default|chi2  ", NULL}},
};

/* The empty adapter: every configuration of the quick set a SKIP row, none
 * run, status 0. */
static void empty_adapter(const char *bindir)
{
    static const char *const rows[] = {"SKIP|matte Kd=1|unsupported: Material: this adapter has no materials yet",
                                       "SKIP|glass default|unsupported", "SKIP|kdsubsurface default|unsupported", NULL};
    char cmd[1024], *out;
    snprintf(cmd, sizeof cmd,
             "'%s/materia-conformance' --impl 'python3 examples/empty_adapter.py' --compare none --quick --threads 1 "
             "--timeout 60 2>&1",
             bindir);
    if (t_check_run("conventions: the empty adapter has every quick configuration skipped, and exits 0", cmd, 0, rows,
                    &out))
        t_check(strstr(out, "\n12 configurations skipped (unsupported)\n") && strstr(out, "\n0 passed, 0 failed"),
                "conventions: the empty adapter's summary counts 12 skipped, 0 passed", "%s", cmd);
    free(out);
}

int main(int argc, char **argv)
{
    const char *bindir = t_tool_bindir(argv[0]);
    size_t i;
    (void)argc;
    if (system("python3 -c 'import sys; sys.exit(sys.version_info < (3, 6))' >/dev/null 2>&1") != 0) {
        t_skip("conventions", "python3 (3.6 or later) is not installed: examples/pbrt_materials.py not run");
        return 0;
    }
    for (i = 0; i < sizeof cases / sizeof cases[0]; ++i) {
        const conv_case *c = &cases[i];
        char cmd[2048], name[160];
        snprintf(cmd, sizeof cmd,
                 "'%s/materia-conformance' --impl 'python3 examples/pbrt_materials.py %s' --compare none --only '%s' "
                 "--samples 1000 --cells 4 --threads 1 --timeout 60 2>&1",
                 bindir, c->flags, c->only);
        snprintf(name, sizeof name, "conventions: %s %s", c->name, c->status ? "fails" : "passes");
        t_check_run(name, cmd, c->status, c->rows, NULL);
    }
    empty_adapter(bindir);
    return t_status();
}
