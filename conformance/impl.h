/*
 * materia-conformance --impl COMMAND: the material-level suite run through
 * any program that speaks the query protocol (docs/PROTOCOL.md), or through
 * materia itself in this process (--impl-inprocess), on the suite's catalog
 * of configurations and on an implementation's own (--catalog FILE). See
 * docs/CONFORMANCE-SUITE.md, "Testing another implementation".
 */
#ifndef CF_IMPL_H
#define CF_IMPL_H

#include "core.h"
#include "materia/tools/query.h"

/* ---- the suite's catalog of configurations (impl_catalog.c) ----------- */
enum {
    CI_FURNACE_LE1 = 1 << 0,   /* albedo <= 1 for every wo */
    CI_TWO_SIDED = 1 << 1,     /* wo from below too */
    CI_SHADING_GAP = 1 << 2,   /* shading normal != geometric: f where the pdf is 0 */
    CI_QUICK = 1 << 3          /* in the reduced set (--quick) */
};

#define CI_MAX_LINES 10
typedef struct cf_impl_config {
    const char *name;
    const char *lines[CI_MAX_LINES]; /* statements and at lines; "@DATA@" is the data directory */
    unsigned flags;
    double lobe_exponent;            /* sharpness, for rounding allowances */
} cf_impl_config;

const cf_impl_config *cf_impl_configs(int *count);
/* Writes the files the catalog names (a MERL table, spectra) into dir. */
int cf_impl_write_data(const char *dir, char *msg, size_t n);
/* c from the catalog's entry (lines with "@DATA@" replaced by data). */
int cf_case_from_config(cf_case *c, const cf_impl_config *k, const char *data);

/* materia in this process on lines (mode, no conventions applied): 0, or
 * -1 and im->msg. im->bsdf is the BSDF. For programs that use materia's
 * answers for the catalog's configurations (make tradeoff). */
int cf_materia_open(cf_impl *im, mt_mode mode, const char *const *lines, int nlines);
void cf_impl_close(cf_impl *im);

/* ---- an implementation's own catalog (catalog_file.c) ------------------- */
/* Reads FILE's configurations (docs/CONFORMANCE-SUITE.md, "Your own
 * configurations") and appends them to *cases (*n of them, *cap
 * allocated). 0, or -1 and msg naming the file and line. */
int cf_catalog_read(const char *path, cf_case **cases, int *n, int *cap, char *msg, size_t nm);

/* ---- --repro DIR (repro.c) --------------------------------------------------- */
typedef struct cf_repro {
    const char *dir;     /* where the files go */
    const char *rerun;   /* the suite's command line to re-run with, up to --only */
} cf_repro;
/* For each failed check of o (c, in run's mode): a file of protocol lines
 * that shows the failure when piped into the implementation, and the
 * command that re-runs that check alone. path of the file written for
 * check k in paths[k] (or ""). 0, or -1 and msg. */
int cf_repro_write(const cf_repro *rp, const cf_run *run, const cf_case *c, const cf_outcome *o,
                   char paths[CK_NCHECK][2048], char *msg, size_t nm);
/* The command that re-runs check k of c alone (its direction w, or -1). */
void cf_repro_command(const cf_repro *rp, const cf_run *run, const cf_case *c, int k, int w, char *out, size_t n);

/* The whole --impl run (argv as given to materia-conformance). */
int cf_impl_main(int argc, char **argv);

#endif
