/* A command's output and the rows in it: see toutput.h. */
#include "support/toutput.h"
#include "support/check.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>

int t_run_output(const char *cmd, char **output)
{
    FILE *p = popen(cmd, "r");
    size_t n = 0, cap = 1 << 16;
    char *buf = malloc(cap);
    int st;
    *output = NULL;
    if (!p || !buf) {
        if (p) pclose(p);
        free(buf);
        return -1;
    }
    for (;;) {
        size_t r;
        if (n + 4096 > cap) {
            char *b = realloc(buf, cap *= 2);
            if (!b) break;
            buf = b;
        }
        r = fread(buf + n, 1, cap - n - 1, p);
        if (!r) break;
        n += r;
    }
    buf[n] = 0;
    st = pclose(p);
    *output = buf;
    return st != -1 && WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

int t_has_row(const char *out, const char *verdict, const char *what)
{
    const char *l = out;
    size_t vlen = strlen(verdict);
    while (l && *l) {
        const char *e = strchr(l, '\n'), *w = what;
        size_t len = e ? (size_t)(e - l) : strlen(l);
        char line[2048];
        int all = 1;
        snprintf(line, sizeof line, "%.*s", (int)(len < sizeof line ? len : sizeof line - 1), l);
        if (!strncmp(line, verdict, vlen) && line[vlen] == ' ') {
            while (all && w) {
                const char *bar = strchr(w, '|');
                char part[256];
                snprintf(part, sizeof part, "%.*s", (int)(bar ? (size_t)(bar - w) : strlen(w)), w);
                all = strstr(line, part) != NULL;
                w = bar ? bar + 1 : NULL;
            }
            if (all) return 1;
        }
        l = e ? e + 1 : NULL;
    }
    return 0;
}

int t_has_rows(const char *out, const char *const *rows)
{
    int i, ok = 1;
    for (i = 0; out && rows && rows[i]; ++i) {
        char verdict[16];
        const char *bar = strchr(rows[i], '|');
        snprintf(verdict, sizeof verdict, "%.*s", (int)(bar ? (size_t)(bar - rows[i]) : strlen(rows[i])), rows[i]);
        if (!bar || !t_has_row(out, verdict, bar + 1)) {
            ok = 0;
            printf("    missing a row \"%s ... %s\"\n", verdict, bar ? bar + 1 : "");
        }
    }
    return ok && out;
}

void t_show_unpassed(const char *out, int max)
{
    const char *l = out;
    int shown = 0;
    while (l && *l && shown < max) {
        const char *e = strchr(l, '\n');
        size_t len = e ? (size_t)(e - l) : strlen(l);
        if (strncmp(l, "PASS", 4)) {
            printf("    | %.*s\n", (int)(len > 300 ? 300 : len), l);
            shown++;
        }
        l = e ? e + 1 : NULL;
    }
}

int t_check_run(const char *name, const char *cmd, int status, const char *const *rows, char **output)
{
    char *out = NULL;
    int rc = t_run_output(cmd, &out), ok = rc == status && out && t_has_rows(out, rows);
    t_check(ok, name, "exit %d (want %d): %s", rc, status, cmd);
    if (!ok && out) t_show_unpassed(out, 16);
    if (output)
        *output = out;
    else
        free(out);
    return ok;
}

const char *t_rows_of(const char *out)
{
    int k;
    for (k = 0; out && k < 3 && (out = strchr(out, '\n')); ++k) out++;
    return out ? out : "";
}

char *t_verdicts_of(const char *rows)
{
    char *v = malloc(strlen(rows) + 1), *at = v;
    while (v && *rows) {
        const char *e = strchr(rows, '\n'), *k;
        size_t len = e ? (size_t)(e - rows) : strlen(rows);
        if (*rows != ' ') {
            k = strstr(rows, " physics ");
            if (!k || k > rows + len) k = strstr(rows, " agreement ");
            if (k && k < rows + len) len = (size_t)(strchr(k + 1, ' ') - rows);
            memcpy(at, rows, len);
            at += len;
            *at++ = '\n';
        }
        rows += e ? (size_t)(e - rows) + 1 : len;
    }
    if (v) *at = 0;
    return v;
}

int t_same_runs(const char *self, const char *other)
{
    char *a, *b;
    int same;
    if (!self || !other) return 0;
    if (strstr(self, "(materia float build")) return !strcmp(t_rows_of(self), t_rows_of(other));
    a = t_verdicts_of(t_rows_of(self));
    b = t_verdicts_of(t_rows_of(other));
    same = a && b && !strcmp(a, b);
    free(a);
    free(b);
    return same;
}
