/*
 * materia-plugin-host PLUGIN.so [--arg STRING]: any plugin of the in-process
 * implementation interface (include/materia/impl.h) as a speaker of the
 * query protocol (docs/PROTOCOL.md) on standard input and output, so that
 * one implementation can be run by the suite both ways (--impl-lib and
 * --impl 'materia-plugin-host PLUGIN.so') and by every tool that speaks the
 * protocol (materia-lobe --impl, a test's own pipe).
 *
 * Statements and "at" lines are kept, in order, and answered "ok"; the
 * plugin builds the configuration from them (its open) when the first
 * eval or sample after them comes, so an error or an unsupported statement
 * is the answer to that query. eval and sample call the plugin with one
 * query each, evals and samples (protocol 3: the conventions answer adds
 * "batch 256") with the whole line's triples at once; the answers are
 * printed as %.9g (a float plugin, with the library's fast exact
 * formatting) or %.17g, or after "numbers hex" as C99 hexadecimal floats. Input is read in large blocks, and the answers are
 * written out whenever every complete line read so far is answered.
 */
#include <dlfcn.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>
#include "materia/config.h"
#include "materia/impl.h"
#include "core/numtext.h"

#define MAX_LINES 256
#define MAX_LINE 65536
#define BATCH 256 /* the most triples of an evals or samples line */

typedef struct host {
    const mt_impl_plugin *p;
    void *state, *cfg;
    int open_status; /* -1 not tried; MT_IMPL_* of the last open */
    char open_msg[1024];
    char mode[32];
    char *lines[MAX_LINES];
    int nlines;
    char pending[MAX_LINE]; /* a statement continued on the next line */
    size_t npending;
    int depth, quoted;      /* its open brackets and quote */
    const char *fmt;        /* "%.9g" or "%.17g" */
    int dbl;
    int hex;                /* after "numbers hex": C99 hexadecimal answers */
} host;

static void reset(host *h)
{
    if (h->cfg) h->p->close(h->cfg);
    h->cfg = NULL;
    h->open_status = -1;
}

/* Numbers of a query: n finite ones after its word, exactly (n > 0), or
 * three and then triples up to -n in all (n < 0). Their count, or -1. */
static int numbers(const char *s, double *v, int n)
{
    int i, most = n > 0 ? n : -n;
    for (i = 0;; ++i) {
        char *e;
        while (*s == ' ' || *s == '\t') s++;
        if (!*s || i == most) break;
        v[i] = mt__strtod(s, &e); /* strtod's value, faster (core/numtext.h) */
        if (e == s || !isfinite(v[i])) return -1;
        s = e;
    }
    if (*s) return -1;
    return n > 0 ? (i == n ? i : -1) : (i >= 6 && i % 3 == 0 ? i : -1);
}

static void num(const host *h, double v, int last)
{
    char b[40];
    if (h->hex)
        mt__format_hex(b, sizeof b, h->dbl ? v : (double)(float)v);
    else if (h->dbl)
        snprintf(b, sizeof b, "%.17g", v);
    else
        mt__format_g9(b, sizeof b, (float)v);
    fputs(b, stdout);
    putchar(last ? '\n' : ' ');
}

static int ensure_open(host *h)
{
    if (h->open_status >= 0) return h->open_status;
    h->open_msg[0] = 0;
    h->open_status = h->p->open(h->state, h->mode, (const char *const *)h->lines, h->nlines, &h->cfg, h->open_msg,
                                sizeof h->open_msg);
    if (h->open_status != MT_IMPL_OK) h->cfg = NULL;
    return h->open_status;
}

static void answer_error(int status, const char *msg)
{
    if (status == MT_IMPL_UNSUPPORTED)
        printf("error unsupported: %s\n", strncmp(msg, "unsupported", 11) ? msg : msg + 11 + strspn(msg + 11, ": "));
    else
        printf("error %s\n", msg[0] ? msg : "the plugin failed (no message)");
}

static void query(host *h, const char *line)
{
    char word[16];
    size_t wl = strcspn(line, " \t");
    const char *rest = line + wl;
    if (wl >= sizeof word) wl = sizeof word - 1;
    memcpy(word, line, wl);
    word[wl] = 0;
    if (!strcmp(word, "version")) {
        printf("protocol 3 %s %s precision %s\n", h->p->name ? h->p->name : "plugin", h->p->version ? h->p->version : "0",
               h->p->precision);
    } else if (!strcmp(word, "conventions")) {
        printf("%s batch %d numbers hex\n", h->p->conventions ? h->p->conventions : "transport importance sample-numbers 3",
               BATCH);
    } else if (!strcmp(word, "numbers")) {
        char m[16];
        if (sscanf(rest, " %15s", m) != 1 || (strcmp(m, "hex") && strcmp(m, "decimal"))) {
            printf("error numbers: hex or decimal\n");
            return;
        }
        h->hex = !strcmp(m, "hex");
        printf("ok\n");
    } else if (!strcmp(word, "mode")) {
        char m[32];
        if (sscanf(rest, " %31s", m) != 1 || (strcmp(m, "pbrt-v2") && strcmp(m, "corrected"))) {
            printf("error mode: needs pbrt-v2 or corrected\n");
            return;
        }
        if (strcmp(m, h->mode)) reset(h);
        snprintf(h->mode, sizeof h->mode, "%s", m);
        printf("ok\n");
    } else if (!strcmp(word, "at")) {
        if (h->nlines == MAX_LINES || !(h->lines[h->nlines] = malloc(strlen(line) + 1))) {
            printf("error too many statements (%d at most)\n", MAX_LINES);
            return;
        }
        strcpy(h->lines[h->nlines++], line);
        reset(h);
        printf("ok\n");
    } else if (!strcmp(word, "eval") || !strcmp(word, "sample") || !strcmp(word, "evals") || !strcmp(word, "samples")) {
        static double v[3 + 3 * BATCH];
        static mt_impl_v3 wo[BATCH], wi[BATCH];
        static float u[BATCH][3];
        static mt_impl_eval e[BATCH];
        static mt_impl_sample smp[BATCH];
        int r, k, i, n, batched = word[strlen(word) - 1] == 's', ev = word[0] == 'e';
        char msg[1024] = "";
        if ((n = numbers(rest, v, batched ? -(3 + 3 * BATCH) : 6)) < 0) {
            if (batched)
                printf("error %s: needs wox woy woz and 1 to %d triples of finite numbers\n", word, BATCH);
            else
                printf("error %s: needs %s\n", word, ev ? "wox woy woz wix wiy wiz" : "wox woy woz uc u1 u2");
            return;
        }
        n = n / 3 - 1;
        if ((r = ensure_open(h)) != MT_IMPL_OK) {
            answer_error(r, h->open_msg);
            return;
        }
        for (i = 0; i < n; ++i) {
            wo[i].x = v[0];
            wo[i].y = v[1];
            wo[i].z = v[2];
            if (ev) {
                wi[i].x = v[3 + 3 * i];
                wi[i].y = v[4 + 3 * i];
                wi[i].z = v[5 + 3 * i];
                continue;
            }
            for (k = 0; k < 3; ++k) {
                u[i][k] = (float)v[3 + 3 * i + k];
                if (!(u[i][k] >= 0 && u[i][k] < 1)) {
                    printf("error %s: uc u1 u2 must be in [0, 1)\n", word);
                    return;
                }
            }
        }
        if (ev) {
            if ((r = h->p->eval(h->cfg, n, wo, wi, e, msg, sizeof msg)) != MT_IMPL_OK) {
                answer_error(r, msg);
                return;
            }
            for (i = 0; i < n; ++i) {
                for (k = 0; k < 3; ++k) num(h, e[i].f[k], 0);
                num(h, e[i].pdf, i == n - 1);
            }
        } else {
            if ((r = h->p->sample(h->cfg, n, wo, (const float(*)[3])u, smp, msg, sizeof msg)) != MT_IMPL_OK) {
                answer_error(r, msg);
                return;
            }
            for (i = 0; i < n; ++i) {
                for (k = 0; k < 3; ++k) num(h, smp[i].wi[k], 0);
                for (k = 0; k < 3; ++k) num(h, smp[i].f[k], 0);
                num(h, smp[i].pdf, 0);
                printf(i == n - 1 ? "%u\n" : "%u ", smp[i].flags);
            }
        }
    } else {
        printf("error unsupported: the plugin interface has no \"%s\" query\n", word);
    }
}

/* A statement line (or the end of one continued): kept, answered "ok". */
static void statement(host *h, const char *text)
{
    if (h->nlines == MAX_LINES || !(h->lines[h->nlines] = malloc(strlen(text) + 1))) {
        printf("error too many statements (%d at most)\n", MAX_LINES);
        return;
    }
    strcpy(h->lines[h->nlines++], text);
    reset(h);
    printf("ok\n");
}

static int is_query(const char *s)
{
    static const char *const words[] = {"version", "conventions", "mode", "at", "eval", "sample",
                                        "rho", "bssrdf", "shading", "texture", "evals", "samples", "numbers"};
    size_t i, wl = strcspn(s, " \t");
    for (i = 0; i < sizeof words / sizeof words[0]; ++i)
        if (wl == strlen(words[i]) && !strncmp(s, words[i], wl)) return 1;
    return 0;
}

static void line(host *h, char *s)
{
    const char *p;
    size_t len = strlen(s);
    if (len && s[len - 1] == '\r') s[--len] = 0;
    if (!h->npending) {
        const char *t = s + strspn(s, " \t");
        if (!*t || *t == '#') return;
        if (is_query(t)) {
            query(h, t);
            return;
        }
    }
    /* a statement, perhaps continued: brackets and quotes balance it */
    for (p = s; *p; ++p) {
        if (*p == '"')
            h->quoted = !h->quoted;
        else if (!h->quoted && *p == '#')
            break;
        else if (!h->quoted && *p == '[')
            h->depth++;
        else if (!h->quoted && *p == ']')
            h->depth--;
    }
    if (h->npending + len + 2 > sizeof h->pending) {
        printf("error a statement longer than %d bytes\n", MAX_LINE);
        h->npending = 0;
        h->depth = h->quoted = 0;
        return;
    }
    if (h->npending) h->pending[h->npending++] = ' ';
    memcpy(h->pending + h->npending, s, len + 1);
    h->npending += len;
    if (h->depth > 0 || h->quoted) return;
    statement(h, h->pending);
    h->npending = 0;
    h->depth = h->quoted = 0;
}

int main(int argc, char **argv)
{
    host h;
    void *dl;
    union {
        void *p;
        mt_impl_entry_fn f;
    } entry;
    static char buf[1 << 20];
    size_t have = 0;
    const char *arg = NULL, *path = NULL;
    char file[4200], msg[1024] = "";
    int i, status = 0;
    for (i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            printf("usage: %s PLUGIN.so [--arg STRING]\n"
                   "Speaks the query protocol (docs/PROTOCOL.md) on standard input and output with the\n"
                   "plugin PLUGIN.so (include/materia/impl.h). --arg: the string its create() receives.\n"
                   "Exit status: 0 at the end of input, 1 when output failed, 2 bad usage or a plugin\n"
                   "that cannot be loaded.\n",
                   argv[0]);
            return 0;
        }
        if (!strcmp(argv[i], "--version")) {
            printf("materia-plugin-host (materia) %s, interface version %d\n", MT_VERSION, MT_IMPL_ABI);
            return 0;
        }
        if (!strcmp(argv[i], "--arg") && i + 1 < argc && !arg)
            arg = argv[++i];
        else if (argv[i][0] != '-' && !path)
            path = argv[i];
        else {
            fprintf(stderr, "%s: unexpected argument \"%s\" (--help)\n", argv[0], argv[i]);
            return 2;
        }
    }
    if (!path) {
        fprintf(stderr, "%s: needs the plugin's path (--help)\n", argv[0]);
        return 2;
    }
    snprintf(file, sizeof file, "%s%.4000s", strchr(path, '/') ? "" : "./", path);
    if (!(dl = dlopen(file, RTLD_NOW | RTLD_LOCAL)) || !(entry.p = dlsym(dl, MT_IMPL_ENTRY)) || !(h.p = entry.f())) {
        const char *e = dl ? NULL : dlerror();
        fprintf(stderr, "%s: %s: %s\n", argv[0], path, e ? e : "exports no " MT_IMPL_ENTRY " or it returned NULL");
        return 2;
    }
    if (h.p->abi != MT_IMPL_ABI || !h.p->open || !h.p->eval || !h.p->sample || !h.p->close || !h.p->precision) {
        fprintf(stderr, "%s: %s: interface version %d (this host's is %d), or a NULL member\n", argv[0], path, h.p->abi,
                MT_IMPL_ABI);
        return 2;
    }
    h.state = NULL;
    if (h.p->create && !(h.state = h.p->create(arg, msg, sizeof msg))) {
        fprintf(stderr, "%s: %s: create failed: %s\n", argv[0], path, msg[0] ? msg : "(no message)");
        return 2;
    }
    h.cfg = NULL;
    h.open_status = -1;
    strcpy(h.mode, "pbrt-v2");
    h.nlines = 0;
    h.npending = 0;
    h.depth = h.quoted = 0;
    h.dbl = !strcmp(h.p->precision, "double");
    h.hex = 0;
    h.fmt = h.dbl ? "%.17g" : "%.9g";
    for (;;) {
        ssize_t got = read(0, buf + have, sizeof buf - 1 - have);
        char *s, *nl;
        if (got < 0 && errno == EINTR) continue;
        if (got <= 0) break;
        have += (size_t)got;
        buf[have] = 0;
        for (s = buf; (nl = memchr(s, '\n', have - (size_t)(s - buf))); s = nl + 1) {
            *nl = 0;
            line(&h, s);
        }
        have -= (size_t)(s - buf);
        memmove(buf, s, have);
        if (have == sizeof buf - 1) { /* a line longer than the buffer */
            printf("error a line longer than %zu bytes\n", sizeof buf - 1);
            have = 0;
        }
        if (fflush(stdout)) status = 1;
    }
    if (have) {
        buf[have] = 0;
        line(&h, buf);
    }
    if (h.npending) printf("error end of input inside a statement (unclosed bracket or string)\n");
    if (fflush(stdout) || ferror(stdout)) status = 1;
    reset(&h);
    for (i = 0; i < h.nlines; ++i) free(h.lines[i]);
    if (h.p->destroy && h.state) h.p->destroy(h.state);
    dlclose(dl);
    return status;
}
