/*
 * Mitsuba 3 behind the query protocol (examples/mitsuba3/materia_mitsuba.py)
 * through materia-conformance --impl --quick --compare none: a real renderer's
 * BSDFs, whose models and transport convention differ from pbrt-v2's, pass
 * every physics check of the configurations it has, and those it lacks are
 * skipped, not failed (docs/TESTING-YOUR-RENDERER.md shows the run and reads
 * it row by row); and so do the three configurations of Mitsuba's own plugins
 * that examples/mitsuba3/mitsuba.catalog marks quick (--catalog: a GGX rough
 * dielectric from both sides, an anisotropic rough conductor, principled).
 *
 * The Python is $MATERIA_PYTHON, else python3. Skipped, with a message saying
 * so, when that Python cannot import mitsuba (CI has no Mitsuba): 0.1 s of CPU.
 * With Mitsuba 3.9.1: 12 + 3 configurations, about 35 s of CPU (measured 15 s
 * for the builtin quick set and 20 s for the catalog's three, each alone).
 * Runs from the source tree (make check's directory).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "support/check.h"
#include "support/toutput.h"
#include "support/ttools.h"

/* The rows the quick set must give: the physics checks of what Mitsuba has
 * pass (glass, mirror and kdsubsurface, delta lobes only, have no density
 * checks), and what it lacks is skipped with the reason. */
static const char *const rows[] = {
    "PASS|matte Kd=1|chi2  ", "PASS|matte Kd=1|furnace  ", "PASS|plastic default|chi2  ",
    "PASS|plastic default|pdf integral", "PASS|plastic default|furnace MC=quad", "PASS|plastic default|reciprocity",
    "PASS|plastic roughness=0.001|chi2  ", "PASS|glass default|furnace  ", "PASS|glass default|helmholtz|(radiance)",
    "PASS|mirror default|furnace  ", "PASS|metal default (copper)|chi2  ", "PASS|metal default (copper)|identity",
    "PASS|uber opacity=0.5|chi2  ", "PASS|mix matte/plastic amount=0.3|chi2  ", "PASS|kdsubsurface default|furnace  ",
    "SKIP|matte Kd=0.8 sigma=20|Oren-Nayar", "SKIP|substrate default|FresnelBlend", "SKIP|translucent default|unsupported",
    "PASS|roughdielectric ggx alpha=0.1 index=1.5|chi2  ", "PASS|roughdielectric ggx alpha=0.1 index=1.5|furnace  |radiance",
    "PASS|roughdielectric ggx alpha=0.1 index=1.5|reciprocity|across", "PASS|roughconductor ggx anisotropic|chi2  ",
    "PASS|principled base_color|pdf integral", NULL};

int main(int argc, char **argv)
{
    const char *py = getenv("MATERIA_PYTHON");
    char cmd[4096];
    (void)argc;
    if (!py || !*py) py = "python3";
    if (strchr(py, '\'')) {
        t_fail("mitsuba", "MATERIA_PYTHON holds a quote: %s", py);
        return t_status();
    }
    snprintf(cmd, sizeof cmd, "'%s' -c 'import mitsuba; mitsuba.set_variant(\"scalar_rgb\")' >/dev/null 2>&1", py);
    if (system(cmd) != 0) {
        t_skip("mitsuba", "'%s' cannot import mitsuba (scalar_rgb): examples/mitsuba3 not run (set MATERIA_PYTHON "
                          "to a Python with Mitsuba 3)", py);
        return 0;
    }
    snprintf(cmd, sizeof cmd,
             "'%s/materia-conformance' --impl \"'%s' examples/mitsuba3/materia_mitsuba.py\" --compare none --quick "
             "--catalog builtin --catalog examples/mitsuba3/mitsuba.catalog --threads 2 --timeout 120 2>&1",
             t_tool_bindir(argv[0]), py);
    t_check_run("mitsuba: Mitsuba 3's BSDFs pass the quick set's physics checks, and its own plugins' quick configurations", cmd, 0, rows, NULL);
    return t_status();
}
