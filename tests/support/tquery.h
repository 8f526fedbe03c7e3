/* Asking an in-process query session (materia/tools/query.h) from a test. A
 * header of its own (not an object of tests/support/, which every test
 * links): the query session pulls in the graphics state, whose texture
 * table test_state replaces with its own. */
#ifndef MT_TEST_TQUERY_H
#define MT_TEST_TQUERY_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "materia/tools/query.h"

/* Sends line to q. n == 0: 1 when the answer is "ok". n > 0: parses n
 * numbers of the answer into v. 0 on any other answer (printed). */
static int t_query_ask(mt_query *q, const char *line, double *v, int n)
{
    char out[512], *p = out, *end;
    int k;
    if (!mt_query_line(q, line, out, sizeof out)) return 0;
    if (n == 0) return !strcmp(out, "ok") ? 1 : (printf("  %s -> %s\n", line, out), 0);
    for (k = 0; k < n; k++) {
        v[k] = strtod(p, &end);
        if (end == p) {
            printf("  %s -> %s\n", line, out);
            return 0;
        }
        p = end;
    }
    return 1;
}

#endif
