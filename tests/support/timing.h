/* Wall-clock timing for the benchmark programs. */
#ifndef MT_TEST_TIMING_H
#define MT_TEST_TIMING_H

/* Seconds of CLOCK_MONOTONIC. */
double t_now(void);
/* The median of v[0..n) (n > 0), sorting v in place. */
double t_median(double *v, int n);

#endif
