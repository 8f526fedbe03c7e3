/*
 * Rows of pbrt-v2's BSDF values (../shared/reference/pbrt-v2-values/
 * bsdf-values.csv: id,kind,wox,woy,woz,wix,wiy,wiz,uc,u1,u2,fr,fg,fb,pdf,flags)
 * and their comparison with a materia BSDF at the project's tolerances: f
 * and pdf within 1e-4 relative, sampled directions within 1e-5, flags equal.
 * pbrt-v2's inputs were floats: they are rounded to float before the query.
 */
#ifndef MT_TEST_PBRT_VALUES_H
#define MT_TEST_PBRT_VALUES_H

#include "materia.h"

typedef struct t_bsdf_row {
    char id[64];
    int eval;      /* 1 for kind=eval, 0 for kind=sample */
    double v[16];  /* v[2..15] as in the file (empty fields 0) */
} t_bsdf_row;

/* Parses one line; 0 when it is not a row of 16 fields. */
int t_bsdf_row_parse(const char *line, t_bsdf_row *row);

/* 1 when b agrees with the row; otherwise 0, and with show the row is
 * printed with materia's answer. *dw (may be NULL) receives the largest
 * direction difference of a sample row. */
int t_bsdf_row_agrees(const mt_bsdf *b, const t_bsdf_row *row, int show, double *dw);

/* Builds the BSDF to compare with one row (in arena a, reset before each
 * row); NULL with err filled on failure. */
typedef mt_bsdf *(*t_bsdf_builder)(void *ctx, mt_arena *a, mt_error *err);

/* Compares every row with this id against the BSDF build makes, and reports
 * under name: in the float build PASS when 400 rows agree, else FAIL (the
 * first three disagreements printed); in the double build SKIP with the
 * count (rows ill-conditioned at float precision differ; the float build
 * carries the verdict); SKIP without ../shared. */
void t_check_pbrt_rows(const char *id, const char *name, t_bsdf_builder build, void *ctx);

#endif
