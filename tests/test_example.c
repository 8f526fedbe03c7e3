/*
 * The worked example (examples/pbrt_materials.py, an independent Python
 * implementation of matte, plastic and mirror) against the published
 * vectors through vectors/check.py: it must pass in both modes, and each of
 * its planted bugs (a pdf 5% high, a Fresnel term from the wrong side, a
 * colour channel 3% low) must be caught. Skipped when python3 is missing.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include "support/check.h"

/* the vectors' configurations of these three materials that the example
 * implements (no textures, no bump maps) */
#define CONFIGS "'^(matte|plastic|mirror) (?!.*(textured|bump))'"

/* Runs the check; its output in out, its exit status returned. */
static int run(const char *impl_args, const char *configs, const char *files, char *out, size_t size)
{
    char cmd[1024];
    FILE *p;
    size_t n = 0;
    int rc;
    snprintf(cmd, sizeof cmd,
             "python3 vectors/check.py --impl 'python3 examples/pbrt_materials.py %s' --only %s --files %s 2>&1",
             impl_args, configs, files);
    if (!(p = popen(cmd, "r"))) return -1;
    while (n + 1 < size && fgets(out + n, (int)(size - n), p)) n += strlen(out + n);
    out[n] = 0;
    rc = pclose(p);
    return rc == -1 ? -1 : WEXITSTATUS(rc);
}

int main(void)
{
    static char out[1 << 16];
    static const char *bugs[] = {"pdf", "fresnel", "colour"};
    int rc, i;
    if (system("python3 -c 'import sys; sys.exit(sys.version_info < (3, 6))' >/dev/null 2>&1") != 0) {
        t_skip("example", "python3 (3.6 or later) is not installed: examples/pbrt_materials.py not run");
        return 0;
    }
    /* its PASS lines count as this test's */
    rc = run("", CONFIGS, "eval,sample", out, sizeof out);
    fputs(out, stdout);
    t_check(rc == 0, "example: matte, plastic and mirror agree with the vectors in both modes",
            "vectors/check.py exited %d", rc);
    for (i = 0; i < 3; ++i) {
        char args[64], name[96];
        snprintf(args, sizeof args, "--bug %s", bugs[i]);
        rc = run(args, "'^plastic default'", "eval", out, sizeof out);
        snprintf(name, sizeof name, "example: the planted bug \"%s\" is caught", bugs[i]);
        /* plastic's default has all three components the bugs touch; its
         * FAIL lines are the expected outcome: not passed through */
        t_check(rc == 1 && strstr(out, "FAIL ") != NULL, name, "vectors/check.py exited %d:\n%s", rc, out);
    }
    return t_status();
}
