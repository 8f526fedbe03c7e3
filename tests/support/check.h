/*
 * A small test vocabulary shared by the unit tests and the conformance suite.
 * Every check prints one line -- "PASS name", "FAIL name: why", "XFAIL name:
 * why" (an expected failure: a pbrt-v2 erratum reproduced) or "SKIP name:
 * why" -- which tools/run-checks.sh counts.
 */
#ifndef MT_TEST_CHECK_H
#define MT_TEST_CHECK_H

#include <stdio.h>
#include "materia_tools.h"

void t_pass(const char *name);
void t_fail(const char *name, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
void t_xfail(const char *name, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
void t_skip(const char *name, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
/* PASS when cond holds, else FAIL with the formatted reason. Returns cond. */
int t_check(int cond, const char *name, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
/* |got - want| <= tol (absolute); names the values on failure. */
int t_near(double got, double want, double tol, const char *name);
/* |got - want| <= rel * max(|want|, floor). */
int t_rel(double got, double want, double rel, double floor, const char *name);
/* Exit status for main: 1 when any check failed. */
int t_status(void);
/* Relative difference |a - b| / max(|a|, |b|, floor). */
double t_reldiff(double a, double b, double floor);
/* Distance in units in the last place between two values, in mt_real. */
double t_ulps(mt_real a, mt_real b);
/* The directory of the shared reference data, or NULL (tests say SKIP). */
const char *t_shared_dir(void);
/* 1 when this build reads and writes the image format ext ("exr", "png",
 * "pfm": mt_image_formats); otherwise prints "SKIP name: ..." naming the
 * build option that left it out and returns 0. A check that needs the
 * format runs only when this is 1 (make check in a NO_EXR=1 or NO_PNG=1
 * build says what it left out). */
int t_has_format(const char *ext, const char *name);

/* T_SANITIZED: 1 in an AddressSanitizer build (gcc's macro or clang's
 * feature test), where tests shrink their workloads. */
#if defined(__SANITIZE_ADDRESS__)
#define T_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define T_SANITIZED 1
#endif
#endif
#ifndef T_SANITIZED
#define T_SANITIZED 0
#endif

#endif
