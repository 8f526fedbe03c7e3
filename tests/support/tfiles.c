/* Temporary directories and files for tests. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "support/tfiles.h"

static char tmpdir[512];

const char *t_tmpdir_create(const char *tag)
{
    const char *base = getenv("TMPDIR");
    if (!base || !*base) base = "/tmp";
    snprintf(tmpdir, sizeof tmpdir, "%s/materia-%s-XXXXXX", base, tag ? tag : "test");
    if (!mkdtemp(tmpdir)) {
        tmpdir[0] = '\0';
        return NULL;
    }
    return tmpdir;
}

const char *t_tmp_path(const char *name)
{
    static char buf[8][1100];
    static int k;
    k = (k + 1) % 8;
    snprintf(buf[k], sizeof buf[k], "%s/%s", tmpdir, name);
    return buf[k];
}

void t_tmpdir_remove(void)
{
    char cmd[600];
    if (!tmpdir[0] || strstr(tmpdir, "/materia-") == NULL || strchr(tmpdir, '\'')) return;
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmpdir);
    if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", tmpdir);
    tmpdir[0] = '\0';
}

const char *t_write_file(const char *rel, const char *text, size_t len)
{
    static char path[1024];
    char *p;
    FILE *f;
    if (!tmpdir[0]) return NULL;
    snprintf(path, sizeof path, "%s/%s", tmpdir, rel);
    for (p = path + strlen(tmpdir) + 1; (p = strchr(p, '/')) != NULL; ++p) {
        *p = '\0';
        mkdir(path, 0700);
        *p = '/';
    }
    if (len == (size_t)-1) len = strlen(text);
    f = fopen(path, "wb");
    if (!f) return NULL;
    if (fwrite(text, 1, len, f) != len) {
        fclose(f);
        return NULL;
    }
    fclose(f);
    return path;
}
