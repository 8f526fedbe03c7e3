/*
 * README.md's example session of materia-query, run: its input lines are
 * given to the tool and its answers must be exactly what the tool prints
 * (float build: the README shows %.9g numbers). A line of the session is an
 * answer when it is "ok", "none", "error ..." or numbers only; every other
 * line is input (a statement's continuation included).
 */
#include <stdlib.h>
#include <string.h>
#include "support/check.h"
#include "support/tfiles.h"
#include "support/ttools.h"

static int is_answer(const char *line)
{
    const char *s = line;
    if (!strcmp(line, "ok") || !strcmp(line, "none") || !strncmp(line, "error ", 6)) return 1;
    while (*s) {
        char *end;
        while (*s == ' ') s++;
        if (!*s) break;
        strtod(s, &end);
        if (end == s || (*end && *end != ' ')) return 0;
        s = end;
    }
    return s != line;
}

int main(int argc, char **argv)
{
    static char readme[1 << 16], input[8192], want[8192], got[8192];
    FILE *f = fopen("README.md", "rb");
    size_t n = f ? fread(readme, 1, sizeof readme - 1, f) : 0;
    char *block, *end, *line;
    size_t ni = 0, nw = 0;
    int nin = 0, nans = 0;
    (void)argc;
    if (f) fclose(f);
    readme[n] = 0;
    t_tool_bindir(argv[0]);
    if (strcmp(mt_precision(), "float") != 0) {
        t_skip("readme session", "the README shows the float build's numbers");
        return t_status();
    }
    block = strstr(readme, "An example session");
    block = block ? strstr(block, "```\n$ materia-query\n") : NULL;
    end = block ? strstr(block + 4, "\n```") : NULL;
    if (!block || !end || !t_tmpdir_create("readme")) {
        t_fail("readme session", "README.md (run from the top directory) has no example session");
        return t_status();
    }
    *end = 0;
    line = block + strlen("```\n$ materia-query\n");
    while (line && *line) {
        char *nl = strchr(line, '\n');
        if (nl) *nl = 0;
        if (is_answer(line)) {
            nw += (size_t)snprintf(want + nw, sizeof want - nw, "%s\n", line);
            nans++;
        } else {
            ni += (size_t)snprintf(input + ni, sizeof input - ni, "%s\n", line);
            nin++;
        }
        line = nl ? nl + 1 : NULL;
    }
    t_write_file("session.txt", input, (size_t)-1);
    {
        int rc = t_tool_run("materia-query", "< session.txt");
        FILE *g = fopen(t_tmp_path("out.txt"), "rb");
        size_t m = g ? fread(got, 1, sizeof got - 1, g) : 0;
        if (g) fclose(g);
        got[m] = 0;
        t_check(rc == 0 && nans > 10 && !strcmp(got, want), "readme: the example session's answers are the tool's",
                "%d input lines, %d answers; the tool (status %d) prints:\n%s\nthe README shows:\n%s", nin, nans,
                rc, got, want);
        t_check(t_file_holds("err.txt", "") && !t_file_holds("err.txt", "warning"),
                "readme: the example session has no warnings", "standard error has some");
    }
    t_tmpdir_remove();
    return t_status();
}
