/* The suite's table: one row per configuration, mode and check. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "conformance.h"

void cf_rows_add(cf_rows *r, const cf_row *row)
{
    if (r->n == r->cap) {
        int cap = r->cap ? 2 * r->cap : 64;
        cf_row *n = realloc(r->rows, (size_t)cap * sizeof *n);
        if (!n) {
            fprintf(stderr, "materia-conformance: out of memory\n");
            exit(2);
        }
        r->rows = n;
        r->cap = cap;
    }
    r->rows[r->n++] = *row;
}

const char *cf_verdict_name(cf_verdict v)
{
    switch (v) {
    case CF_PASS: return "PASS";
    case CF_FAIL: return "FAIL";
    case CF_XFAIL: return "XFAIL";
    case CF_SKIP: return "SKIP";
    case CF_INFO: return "INFO";
    }
    return "?";
}

void cf_rows_print(const cf_rows *r)
{
    int i;
    for (i = 0; i < r->n; ++i) {
        const cf_row *x = &r->rows[i];
        printf("%-5s %-50s %-9s %-15s %-9s %-62s %-18s%s%s\n", cf_verdict_name(x->verdict), x->subject, x->mode,
               x->check, x->kind[0] ? x->kind : "physics", x->statistic, x->bound, x->note[0] ? " " : "", x->note);
        if (x->detail[0]) fputs(x->detail, stdout);
    }
    fflush(stdout);
}

int cf_rows_count(const cf_rows *r, cf_verdict v, const char *kind)
{
    int i, n = 0;
    for (i = 0; i < r->n; ++i)
        n += r->rows[i].verdict == v && (!kind || !strcmp(r->rows[i].kind[0] ? r->rows[i].kind : "physics", kind));
    return n;
}

void cf_rows_free(cf_rows *r)
{
    free(r->rows);
    r->rows = NULL;
    r->n = r->cap = 0;
}
