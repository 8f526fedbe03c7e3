/*
 * The text protocol's fast form (protocol 3, docs/PROTOCOL.md, "Batched
 * queries" and "Hexadecimal numbers"), proven through the suite:
 *
 *  - materia-query and the plugin host announce "batch 256 numbers hex";
 *    with batched lines of hexadecimal numbers the suite's rows are those
 *    of materia in its own process, value for value, in either precision
 *    (hexadecimal carries the suite's float inputs exactly); with one
 *    decimal query a line (--plain) too in float, and the same verdicts in
 *    double (a double implementation reads the float inputs' 9 digits), on
 *    a few configurations;
 *  - an implementation that answers a batched line "error ..." (here
 *    materia-query fed "evalz"/"samplez" for "evals"/"samples", which it
 *    takes for an unknown statement) is asked again one query a line: the
 *    same rows as the plain run;
 *  - an answer of the wrong shape to a batched line (one value short) is a
 *    protocol failure whose message names the batched line and its size.
 *
 * Cost: about 7 s of one core (five --quick runs of four configurations,
 * three of one).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "support/toutput.h"
#include "support/ttools.h"

static int failures;

static void verdict(int ok, const char *name, const char *cmd, const char *out)
{
    printf("%s batch: %s\n", ok ? "PASS" : "FAIL", name);
    if (!ok) {
        failures++;
        printf("    command: %s\n", cmd);
        t_show_unpassed(out ? out : "(no output)", 12);
    }
}

/* Runs cmd (stderr joined) and keeps its output; 1 when it exited with want. */
static int run(const char *cmd, int want, char **out)
{
    int st = t_run_output(cmd, out);
    if (st != want) printf("    exit %d, want %d: %s\n", st, want, cmd);
    return st == want && *out;
}

int main(int argc, char **argv)
{
    static const char *const only = "--only '^(matte Kd=1|plastic default|glass default|mix matte/plastic amount=0.3)$'";
    char bin[1100], plugins[1100], cmd[8192];
    char *self = NULL, *plain = NULL, *batched = NULL, *hplain = NULL, *hbatched = NULL;
    char *fallback = NULL, *onealone = NULL, *bad = NULL;
    int ok;
    (void)argc;
    snprintf(bin, sizeof bin, "%.1000s", t_tool_bindir(argv[0]));
    snprintf(plugins, sizeof plugins, "%.1000s/../plugins", bin);

    /* materia in this process, materia-query with batched lines (its
     * default) and with one query a line */
    snprintf(cmd, sizeof cmd, "%s/materia-conformance --impl-inprocess --quick --threads 2 %s 2>&1", bin, only);
    ok = run(cmd, 0, &self);
    snprintf(cmd, sizeof cmd, "%s/materia-conformance --impl %s/materia-query --quick --threads 2 %s 2>&1", bin, bin, only);
    ok = run(cmd, 0, &batched) && ok;
    snprintf(cmd, sizeof cmd, "%s/materia-conformance --impl %s/materia-query --plain --quick --threads 2 %s 2>&1", bin,
             bin, only);
    ok = run(cmd, 0, &plain) && ok;
    verdict(ok && strstr(batched, "; lines: evals/samples of up to 256 triples, hexadecimal numbers\n") &&
                strstr(plain, "; lines: one query each\n") && strstr(t_rows_of(plain), "PASS  glass default") &&
                !strcmp(t_rows_of(self), t_rows_of(batched)) && t_same_runs(self, plain),
            "materia-query: the same rows with batched lines and one query a line", cmd, batched);

    /* the plugin host: the same */
    snprintf(cmd, sizeof cmd,
             "%s/materia-conformance --impl '%s/materia-plugin-host %s/materia_plugin.so' --quick --threads 2 %s 2>&1", bin,
             bin, plugins, only);
    ok = run(cmd, 0, &hbatched) && self;
    snprintf(cmd, sizeof cmd,
             "%s/materia-conformance --impl '%s/materia-plugin-host %s/materia_plugin.so' --plain --quick --threads 2 %s "
             "2>&1",
             bin, bin, plugins, only);
    ok = run(cmd, 0, &hplain) && ok;
    verdict(ok && strstr(hbatched, "; lines: evals/samples of up to 256 triples, hexadecimal numbers\n") &&
                !strcmp(t_rows_of(self), t_rows_of(hbatched)) && t_same_runs(self, hplain) &&
                strstr(t_rows_of(hplain), "PASS  glass default"),
            "the plugin host: the same rows with batched lines and one query a line", cmd, hbatched);

    /* an error answer to every batched line: asked again one a line (one
     * configuration, one check: sed -u reads a byte a system call) */
    snprintf(cmd, sizeof cmd,
             "%s/materia-conformance --impl \"sed -u -e 's/^evals /evalz /' -e 's/^samples /samplez /' | "
             "%s/materia-query\" --quick --threads 1 --only '^plastic default$' --check identity 2>&1",
             bin, bin);
    ok = run(cmd, 0, &fallback);
    snprintf(cmd, sizeof cmd,
             "%s/materia-conformance --impl %s/materia-query --plain --quick --threads 1 --only '^plastic default$' "
             "--check identity 2>&1",
             bin, bin);
    ok = run(cmd, 0, &onealone) && ok;
    verdict(ok && strstr(t_rows_of(onealone), "PASS  plastic default") && t_same_runs(onealone, fallback),
            "an error answer to a batched line: the suite asks again one query a line (the same rows)", cmd, fallback);

    /* one value short in every answer of more than 8 values (eight spaces) */
    snprintf(cmd, sizeof cmd,
             "%s/materia-conformance --impl \"%s/materia-query | sed -u '/\\\\( [^ ]*\\\\)\\\\{8\\\\}/s/ [^ ]*$//'\" "
             "--quick --threads 1 --only '^plastic default$' 2>&1",
             bin, bin);
    ok = run(cmd, 1, &bad);
    verdict(ok && t_has_row(bad, "FAIL", "plastic default|protocol|answered too few values (") &&
                t_has_row(bad, "FAIL", "to the batched line 1 of |\"samples 0x") &&
                t_has_row(bad, "FAIL", "triples, 8 values each)"),
            "a batched answer one value short: a protocol failure naming the batched line", cmd, bad);
    free(self);
    free(plain);
    free(batched);
    free(hplain);
    free(hbatched);
    free(fallback);
    free(onealone);
    free(bad);
    return failures ? 1 : 0;
}
