/*
 * Runs a fuzz target over files without a fuzzing engine, once each: the
 * regression test of make check (any C compiler; under SANITIZE= the
 * sanitizers watch every run).
 *
 *   fuzz-NAME [FILE|DIR]...     the files named, and every file of each DIR
 *   fuzz-NAME                   every file of fuzz/corpus/NAME (NAME: the
 *                               program's name after "fuzz-")
 *
 * A crash or a sanitizer report ends the program with its status (make
 * check counts that as a failure); an input that runs for more than
 * FUZZ_TIMEOUT seconds (60 by default) ends it with a FAIL line naming the
 * input. Prints one PASS line with the number of inputs run.
 */
#include <dirent.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "fuzz.h"

static const char *current;
static char name[64];

static void on_alarm(int sig)
{
    static const char msg[] = "FAIL fuzz corpus: an input ran past the time limit: ";
    (void)sig;
    if (write(2, msg, sizeof msg - 1) < 0 || write(2, current, strlen(current)) < 0 ||
        write(2, "\n", 1) < 0) {
    }
    _exit(1);
}

static int run_file(const char *path, unsigned timeout)
{
    FILE *f = fopen(path, "rb");
    unsigned char *buf = NULL;
    size_t n = 0, cap = 0;
    if (!f) {
        printf("FAIL fuzz corpus %s: cannot open %s\n", name, path);
        return 0;
    }
    for (;;) {
        size_t got;
        if (n == cap) {
            unsigned char *nb = realloc(buf, cap = cap ? 2 * cap : 4096);
            if (!nb) {
                free(buf);
                fclose(f);
                printf("FAIL fuzz corpus %s: out of memory reading %s\n", name, path);
                return 0;
            }
            buf = nb;
        }
        got = fread(buf + n, 1, cap - n, f);
        n += got;
        if (got == 0) break;
    }
    fclose(f);
    current = path;
    alarm(timeout);
    LLVMFuzzerTestOneInput(buf, n);
    alarm(0);
    free(buf);
    return 1;
}

static int cmp(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }

/* Every regular file of dir, in name order; -1 when dir cannot be read. */
static int run_dir(const char *dir, unsigned timeout)
{
    DIR *d = opendir(dir);
    struct dirent *e;
    char **names = NULL;
    int n = 0, cap = 0, i, ran = 0;
    if (!d) return -1;
    while ((e = readdir(d))) {
        if (e->d_name[0] == '.') continue;
        if (n == cap) {
            char **nn = realloc(names, (size_t)(cap = cap ? 2 * cap : 64) * sizeof *nn);
            if (!nn) break;
            names = nn;
        }
        names[n] = malloc(strlen(dir) + strlen(e->d_name) + 2);
        if (!names[n]) break;
        sprintf(names[n], "%s/%s", dir, e->d_name);
        n++;
    }
    closedir(d);
    qsort(names, (size_t)n, sizeof *names, cmp);
    for (i = 0; i < n; ++i) {
        struct stat sb;
        if (stat(names[i], &sb) == 0 && S_ISREG(sb.st_mode)) ran += run_file(names[i], timeout);
        free(names[i]);
    }
    free(names);
    return ran;
}

int main(int argc, char **argv)
{
    const char *base = strrchr(argv[0], '/'), *env = getenv("FUZZ_TIMEOUT");
    unsigned timeout = env && atoi(env) > 0 ? (unsigned)atoi(env) : 60;
    char corpus[128];
    int i, ran = 0;
    base = base ? base + 1 : argv[0];
    snprintf(name, sizeof name, "%s", strncmp(base, "fuzz-", 5) == 0 ? base + 5 : base);
    signal(SIGALRM, on_alarm);
    if (argc < 2) {
        snprintf(corpus, sizeof corpus, "fuzz/corpus/%s", name);
        ran = run_dir(corpus, timeout);
        if (ran <= 0) {
            printf("FAIL fuzz corpus %s: no inputs in %s (run from the source tree)\n", name,
                   corpus);
            return 1;
        }
    }
    for (i = 1; i < argc; ++i) {
        struct stat sb;
        int r = stat(argv[i], &sb) == 0 && S_ISDIR(sb.st_mode) ? run_dir(argv[i], timeout)
                                                                : run_file(argv[i], timeout);
        if (r < 0) {
            printf("FAIL fuzz corpus %s: cannot read %s\n", name, argv[i]);
            return 1;
        }
        ran += r;
    }
    printf("PASS fuzz corpus %s: %d inputs, none crashed, hung or leaked\n", name, ran);
    return 0;
}
