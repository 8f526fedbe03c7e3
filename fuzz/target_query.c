/*
 * Fuzz target: a query session (mt_query_line), the input taken as a
 * stream of lines, then mt_query_finish. Relative file names resolve
 * against the target's empty temporary directory.
 */
#include <stdlib.h>
#include <string.h>
#include "fuzz.h"
#include "materia/measured.h"
#include "materia/mipmap.h"
#include "materia/tools/query.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *text = fz_text(data, size), *line, out[4096];
    mt_error err;
    mt_query *q;
    if (!text) return 0;
    mt_error_clear(&err);
    q = mt_query_create(fz_dir(), &err);
    for (line = text; q && line;) {
        char *nl = strchr(line, '\n');
        if (nl) *nl = '\0';
        mt_query_line(q, line, out, sizeof out);
        line = nl ? nl + 1 : NULL;
    }
    if (q) mt_query_finish(q, out, sizeof out);
    mt_query_destroy(q);
    mt_mipmap_cache_clear();
    mt_measured_cache_clear();
    free(text);
    return 0;
}
