#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>
#include "support/check.h"
#include "support/tfiles.h"
#include "support/ttools.h"

static char bindir[1024];

const char *t_tool_bindir(const char *argv0)
{
    const char *slash = strrchr(argv0, '/');
    char cwd[512];
    int len = slash ? (int)(slash - argv0) : 1;
    if (!slash) argv0 = ".";
    /* absolute: the tools run in the test's directory */
    if (argv0[0] == '/' || !getcwd(cwd, sizeof cwd))
        snprintf(bindir, sizeof bindir, "%.*s/../bin", len, argv0);
    else
        snprintf(bindir, sizeof bindir, "%s/%.*s/../bin", cwd, len, argv0);
    return bindir;
}

int t_tool_run(const char *toolname, const char *args)
{
    char cmd[4096];
    int rc;
    snprintf(cmd, sizeof cmd, "cd '%s' && '%s/%s' </dev/null %s >out.txt 2>err.txt", t_tmp_path(""), bindir,
             toolname, args);
    rc = system(cmd);
    return rc != -1 && WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

int t_file_holds(const char *name, const char *text)
{
    static char buf[65536];
    FILE *f = fopen(t_tmp_path(name), "r");
    size_t n;
    if (!f) return 0;
    n = fread(buf, 1, sizeof buf - 1, f);
    fclose(f);
    buf[n] = 0;
    return strstr(buf, text) != NULL;
}

void t_tool_check(const char *name, const char *toolname, const char *args, int want, const char *file,
                  const char *text)
{
    int rc = t_tool_run(toolname, args);
    t_check(rc == want && t_file_holds(file, text), name, "exit %d (want %d), %s %s \"%s\"", rc, want, file,
            t_file_holds(file, text) ? "holds" : "lacks", text);
}
