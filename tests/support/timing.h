/* Timing for the benchmark programs. */
#ifndef MT_TEST_TIMING_H
#define MT_TEST_TIMING_H

/* Seconds of CLOCK_MONOTONIC. */
double t_now(void);
/* Seconds of CPU time of the calling thread: on a shared, loaded machine it
 * leaves out the time other processes hold the core (single-thread figures). */
double t_cpu_now(void);
/* The median of v[0..n) (n > 0), sorting v in place. */
double t_median(double *v, int n);

#endif
