/*
 * The in-process implementation interface (include/materia/impl.h), proven:
 *
 *  - materia's own BSDFs as a plugin (--impl-lib), through the plugin host
 *    as a protocol speaker (--impl 'materia-plugin-host PLUGIN'), linked
 *    into a program that calls mt_impl_run_suite, and materia in this
 *    process: the same rows, value for value, every one passed;
 *  - the C example (examples/plugin/lambert_plugin.c) passes physics, its
 *    unsupported materials skipped, by both paths;
 *  - a plugin with a smooth 1% error planted (tests/plugin_planted.c) is
 *    failed at --power 0.01, physics alone, in seeded runs (--quick, the
 *    one check that catches it): a sampler warp on matte (chi2: the warp of
 *    its disk's u1 moves directions in azimuth, which the mean of |cos
 *    theta_i| cannot see) and on plastic (mean wi: the warp of its half
 *    vector), a pdf shape (mean wi), an f shape (reciprocity); the honest
 *    plugin passes the same runs; the POWER row shows what it could catch;
 *  - bad plugins and bad options: exit 2 with a message naming them.
 *
 * Cost: about 35 s of one core (the 14 --power runs dominate, 2 s each).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "support/toutput.h"

static char bin[1100], tests_dir[1024], plugins[1100];
static int failures;

static void verdict(int ok, const char *name, const char *cmd, const char *out)
{
    printf("%s plugin: %s\n", ok ? "PASS" : "FAIL", name);
    if (!ok) {
        failures++;
        printf("    command: %s\n", cmd);
        t_show_unpassed(out, 12);
    }
}

/* Runs cmd (stderr joined): its status must be want and each row present;
 * the output in *keep when keep is not NULL. */
static void expect(const char *name, const char *cmd, int want, const char *const *rows, char **keep)
{
    char *out = NULL;
    int st = t_run_output(cmd, &out), ok = st == want && t_has_rows(out, rows);
    if (ok && want == 0 && !strstr(out, " passed, 0 failed")) ok = 0;
    if (!ok) printf("    exit %d, want %d\n", st, want);
    verdict(ok, name, cmd, out);
    if (keep)
        *keep = out;
    else
        free(out);
}

int main(int argc, char **argv)
{
    static const char *const only = "--only '^(matte Kd=1|plastic default|glass default|mix matte/plastic amount=0.3)$'";
    char cmd[8192];
    char *self = NULL, *lib = NULL, *host = NULL, *linked = NULL;
    char *slash;
    int seed;
    (void)argc;
    snprintf(tests_dir, sizeof tests_dir, "%.1000s", argv[0]);
    slash = strrchr(tests_dir, '/');
    if (slash)
        *slash = 0;
    else
        snprintf(tests_dir, sizeof tests_dir, ".");
    snprintf(bin, sizeof bin, "%.1000s/../bin", tests_dir);
    snprintf(plugins, sizeof plugins, "%.1000s/../plugins", tests_dir);

    /* one implementation, four paths, the same rows */
    snprintf(cmd, sizeof cmd, "%s/materia-conformance --impl-inprocess --quick --threads 2 %s 2>&1", bin, only);
    expect("materia in this process passes", cmd, 0, NULL, &self);
    snprintf(cmd, sizeof cmd, "%s/materia-conformance --impl-lib %s/materia_plugin.so --quick --threads 2 %s 2>&1", bin,
             plugins, only);
    expect("materia's plugin passes (--impl-lib)", cmd, 0, NULL, &lib);
    snprintf(cmd, sizeof cmd,
             "%s/materia-conformance --impl '%s/materia-plugin-host %s/materia_plugin.so' --quick --threads 2 %s 2>&1", bin,
             bin, plugins, only);
    expect("materia's plugin passes through the plugin host (--impl)", cmd, 0, NULL, &host);
    snprintf(cmd, sizeof cmd, "%s/plugin-linked --quick --threads 2 %s 2>&1", tests_dir, only);
    expect("materia's plugin passes linked into a program (mt_impl_run_suite)", cmd, 0, NULL, &linked);
    /* the host speaks the text protocol (t_same_runs: verdicts in double);
     * the three in-process paths are the same value for value */
    verdict(self && lib && linked && !strcmp(t_rows_of(self), t_rows_of(lib)) && t_same_runs(self, host) &&
                !strcmp(t_rows_of(self), t_rows_of(linked)) && strstr(t_rows_of(self), "PASS  glass default"),
            "in this process, as a plugin, through the host and linked: the same rows", "(the four above)", "");
    free(self);
    free(lib);
    free(host);
    free(linked);

    /* the C example, both ways: physics passed, the rest skipped */
    {
        static const char *const rows[] = {"PASS|matte Kd=1|chi2|physics", "PASS|matte Kd=1|furnace MC=quad",
                                           "PASS|matte Kd=1|reciprocity", "SKIP|plastic default|unsupported|material",
                                           "POWER|matte Kd=1|caught in 95% of runs: a sampler warp of", NULL};
        snprintf(cmd, sizeof cmd, "%s/materia-conformance --impl-lib %s/lambert_plugin.so --compare none --quick --threads 2 2>&1",
                 bin, plugins);
        expect("the C example plugin passes physics, the materials it lacks skipped", cmd, 0, rows, NULL);
        snprintf(cmd, sizeof cmd,
                 "%s/materia-conformance --impl '%s/materia-plugin-host %s/lambert_plugin.so' --compare none --quick "
                 "--threads 2 2>&1",
                 bin, bin, plugins);
        expect("the C example through the plugin host: the same", cmd, 0, rows, NULL);
    }

    /* a 1% smooth error, physics alone, at --power 0.01, each caught by the
     * check that sees it; the honest plugin passes the same seeded runs */
    {
        static const struct {
            const char *arg, *config, *check, *caught;
            int seeds;
        } planted[] = {
            {"warp 0.01", "matte Kd=1", "chi2", "FAIL|matte Kd=1|chi2|physics", 2},
            {"warp 0.01", "plastic default", "mean wi", "FAIL|plastic default|mean wi|physics", 2},
            {"pdf 0.01", "matte Kd=1", "mean wi", "FAIL|matte Kd=1|mean wi|physics", 2},
            {"f 0.01", "matte Kd=1", "reciprocity", "FAIL|matte Kd=1|reciprocity|physics", 1},
        };
        size_t j;
        for (j = 0; j < sizeof planted / sizeof planted[0]; ++j)
            for (seed = 1; seed <= planted[j].seeds; ++seed) {
                int k;
                for (k = 0; k < 2; ++k) {
                    char name[200], pass[120], power[80];
                    /* the POWER row comes with the statistical checks */
                    int stat = strcmp(planted[j].check, "reciprocity") != 0;
                    const char *caught[] = {planted[j].caught, NULL}, *honest[] = {pass, stat ? power : NULL, NULL};
                    snprintf(pass, sizeof pass, "PASS|%s|%s|physics", planted[j].config, planted[j].check);
                    snprintf(power, sizeof power, "POWER|%s|a pdf shape of", planted[j].config);
                    snprintf(cmd, sizeof cmd,
                             "%s/materia-conformance --impl-lib %s/plugin_planted.so --impl-arg '%s' --power 0.01 --quick "
                             "--compare none --only '^%s$' --check '%s' --seed %d --threads 1 2>&1",
                             bin, tests_dir, k ? "none 0" : planted[j].arg, planted[j].config, planted[j].check, seed);
                    snprintf(name, sizeof name, "%s on %s: %s at --power 0.01 (seed %d)", k ? "honest" : planted[j].arg,
                             planted[j].config, k ? "passes the same run" : "caught by its check", seed);
                    expect(name, cmd, k ? 0 : 1, k ? honest : caught, NULL);
                }
            }
    }

    /* bad plugins, bad options */
    snprintf(cmd, sizeof cmd, "%s/materia-conformance --impl-lib %s/no-such-plugin.so --quick 2>&1", bin, tests_dir);
    {
        static const char *const rows[] = {NULL};
        char *out = NULL;
        int st = t_run_output(cmd, &out);
        verdict(st == 2 && out && strstr(out, "--impl-lib: cannot load") && strstr(out, "no-such-plugin.so"),
                "a plugin that cannot be loaded: exit 2, named", cmd, out);
        free(out);
        snprintf(cmd, sizeof cmd, "%s/materia-conformance --impl-lib %s/../bin/materia-query --quick 2>&1", bin, tests_dir);
        st = t_run_output(cmd, &out);
        verdict(st == 2 && out && strstr(out, "--impl-lib:"), "a file that is no plugin: exit 2", cmd, out);
        free(out);
        snprintf(cmd, sizeof cmd, "%s/materia-conformance --impl-lib %s/plugin_planted.so --impl-arg 'bent 0.01' --quick 2>&1",
                 bin, tests_dir);
        st = t_run_output(cmd, &out);
        verdict(st == 2 && out && strstr(out, "create(\"bent 0.01\") failed"), "a plugin whose create fails: exit 2, its message",
                cmd, out);
        free(out);
        snprintf(cmd, sizeof cmd, "%s/materia-conformance --impl-inprocess --impl-arg x --quick 2>&1", bin);
        st = t_run_output(cmd, &out);
        verdict(st == 2 && out && strstr(out, "--impl-arg needs --impl-lib"), "--impl-arg without --impl-lib: exit 2", cmd, out);
        free(out);
        snprintf(cmd, sizeof cmd, "%s/materia-conformance --impl-inprocess --power 0.0001 --quick 2>&1", bin);
        st = t_run_output(cmd, &out);
        verdict(st == 2 && out && strstr(out, "--power: \"0.0001\""), "--power out of range: exit 2", cmd, out);
        free(out);
        (void)rows;
    }
    /* the host answers the protocol's version and conventions, and an
     * unsupported material as the protocol says */
    {
        char *out = NULL;
        snprintf(cmd, sizeof cmd,
                 "printf 'version\\nconventions\\nMaterial \"plastic\"\\neval 0 0 1 0 0 1\\nMaterial \"matte\" \"rgb Kd\" "
                 "[1 1 1]\\neval 0 0 1 0 0 1\\n' | %s/materia-plugin-host %s/lambert_plugin.so 2>&1",
                 bin, plugins);
        t_run_output(cmd, &out);
        verdict(out && !strcmp(out, "protocol 3 lambert_plugin 1.0 precision double\n"
                                   "transport importance sample-numbers 3 batch 256 numbers hex\n"
                                   "ok\nerror unsupported: material \"plastic\": only matte\nok\n"
                                   "0.31830988618379069 0.31830988618379069 0.31830988618379069 0.31830988618379069\n"),
                "the plugin host speaks the protocol", cmd, out);
        free(out);
    }
    return failures != 0;
}
