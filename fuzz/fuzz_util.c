/* The fuzz targets' temporary files (fuzz.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "fuzz.h"

static char dir[512];
static char written[16][8]; /* the files made, removed at exit */
static int nwritten;

static void cleanup(void)
{
    int i;
    for (i = 0; i < nwritten; ++i) {
        char path[1200];
        snprintf(path, sizeof path, "%s/input%s", dir, written[i]);
        unlink(path);
    }
    if (dir[0]) rmdir(dir);
}

const char *fz_dir(void)
{
    if (!dir[0]) {
        const char *tmp = getenv("TMPDIR");
        snprintf(dir, sizeof dir, "%s/materia-fuzz-XXXXXX", tmp && *tmp ? tmp : "/tmp");
        if (!mkdtemp(dir)) {
            dir[0] = '\0';
            return NULL;
        }
        atexit(cleanup);
    }
    return dir;
}

const char *fz_write_input(const uint8_t *data, size_t size, const char *ext)
{
    static char path[600];
    FILE *f;
    int i, known = 0;
    if (!fz_dir() || strlen(ext) >= sizeof written[0]) return NULL;
    snprintf(path, sizeof path, "%s/input%s", dir, ext);
    for (i = 0; i < nwritten; ++i) known |= strcmp(written[i], ext) == 0;
    if (!known && nwritten < (int)(sizeof written / sizeof written[0]))
        strcpy(written[nwritten++], ext);
    unlink(path);
    f = fopen(path, "wb");
    if (!f) return NULL;
    if (size && fwrite(data, 1, size, f) != size) {
        fclose(f);
        return NULL;
    }
    return fclose(f) == 0 ? path : NULL;
}

char *fz_text(const uint8_t *data, size_t size)
{
    char *t = malloc(size + 1);
    if (!t) return NULL;
    if (size) memcpy(t, data, size);
    t[size] = '\0';
    return t;
}
