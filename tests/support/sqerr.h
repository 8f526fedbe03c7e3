/*
 * The squared error of an image against a reference that carries noise of its
 * own, with that noise taken out: the samples-per-pixel measurement
 * (tradeoff/imgerr.c, docs/TRADEOFF.md section 2), tested by tests/test_sqerr.c.
 *
 * a is the image under test, b the reference: a render whose pixels are means
 * of samples independent of a's, and vb its estimated variance of the mean per
 * pixel and channel (materia-render --variance, mt_imgacc_finish). With mu =
 * E[b] and a independent of b, the cross term of (a - b)^2 = ((a - mu) -
 * (b - mu))^2 has expectation 0, so
 *
 *     E[(a - b)^2] = E[(a - mu)^2] + Var(b),
 *
 * and mean((a - b)^2 - vb) over pixels and colour channels estimates a's mean
 * squared error against mu without bias whenever vb is unbiased for Var(b).
 * Without the subtraction the reference's noise inflates the estimate by
 * Var(b) / E[(a - mu)^2], which for two Monte Carlo renders is the ratio of
 * the sample counts (25% for a reference at 4 times the samples).
 *
 * Where vb comes from: a renderer's variance image (s^2 / n from the pixel's
 * own samples) is unbiased only for independent samples; for stratified or
 * low-discrepancy samples it overestimates Var(b), and the subtraction then
 * takes away too much. Two renders r1, r2 with independent seeds give an
 * estimate that needs no model of the samples: b = (r1 + r2) / 2 and
 * vb = (r1 - r2)^2 / 4, since E[(r1 - r2)^2] = Var(r1) + Var(r2) = 4 Var(b)
 * (t_sqerr_pair).
 */
#ifndef MT_TEST_SQERR_H
#define MT_TEST_SQERR_H

#include <stddef.h>
#include "materia/image.h"

typedef struct t_sqerr {
    size_t n;          /* values compared: pixels x colour channels */
    double mse_raw;    /* mean (a - b)^2 */
    double ref_var;    /* mean vb: the reference's expected share of mse_raw */
    double mse;        /* mse_raw - ref_var: a's mean squared error against E[b]
                        * (by chance below 0 when a is about as good as b) */
    double relmse_raw; /* mean (a - b)^2 / (b^2 + 0.01) (Rousselle et al. 2011) */
    double relmse;     /* mean ((a - b)^2 - vb) / (b^2 + 0.01): unbiased up to
                        * terms in the square of b's relative noise (b is in the
                        * weight too) */
    double a_var;      /* mean va when va is given, else -1 */
} t_sqerr;

/* Colour channels as materia's comparisons take them (Y of a one-channel image,
 * R, G, B otherwise: the alpha of an RGBA EXR is ignored). a and b must have
 * the same size and the same colour channel count, and so must vb and va when
 * given (either may be NULL: vb NULL counts as a reference without noise);
 * a variance must be finite and not negative. Returns 0, or -1 with the reason
 * in msg. */
int t_sqerr_compute(const mt_image *a, const mt_image *va, const mt_image *b, const mt_image *vb,
                    t_sqerr *out, char *msg, size_t msglen);

/* The reference of two independent renders of the same image, r1 and r2: the
 * mean (r1 + r2) / 2 and its variance estimate (r1 - r2)^2 / 4 per pixel and
 * channel (mt_imgacc of the two). 0, or -1 with the reason in msg; the caller
 * frees *mean and *var with mt_image_destroy. */
int t_sqerr_pair(const mt_image *r1, const mt_image *r2, mt_image *mean, mt_image *var, char *msg,
                 size_t msglen);

#endif
