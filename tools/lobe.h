/*
 * The layout of materia-lobe's picture (included by the tool and by
 * tests/test_lobe.c, which checks pictures against it). One row per
 * implementation, and a third for their difference; each row has three
 * lat-long maps of LL_W x LL_H (x: phi from 0 to 2 pi; y: theta from 0, +z,
 * at the top, to pi) and a polar plot LL_H wide, each with a title above
 * and a colour bar below. The header has two lines, one per implementation
 * and the statements wrapped at the picture's width.
 */
#ifndef MT_TOOLS_LOBE_H
#define MT_TOOLS_LOBE_H

#define LL_W 256
#define LL_H 128
#define GAP 6    /* around and between panels */
#define LINE 10  /* a header line */
#define TITLE 10 /* a panel's title */
#define BAR 19   /* a panel's colour bar and its labels */

#define LOBE_WIDTH (GAP + 3 * (LL_W + GAP) + LL_H + GAP)
#define LOBE_HEADER(nimpl, stmt_lines) (GAP + LINE * (2 + (nimpl) + (stmt_lines)))
#define LOBE_HEIGHT(nimpl, stmt_lines, rows) (LOBE_HEADER(nimpl, stmt_lines) + (rows) * (TITLE + LL_H + BAR + GAP))
/* the top-left pixel of row r's k-th map */
#define LOBE_MAP_X(k) (GAP + (k) * (LL_W + GAP))
#define LOBE_MAP_Y(nimpl, stmt_lines, r) (LOBE_HEADER(nimpl, stmt_lines) + (r) * (TITLE + LL_H + BAR + GAP) + TITLE)

#endif
