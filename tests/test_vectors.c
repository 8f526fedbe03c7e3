/*
 * The published conformance vectors (vectors/, format in vectors/README.md).
 *
 *   test_vectors --write DIR   writes them: DIR/configs.tsv, DIR/points.csv,
 *                              DIR/data/ and DIR/<precision>/ (make vectors runs it
 *                              in the float and the double build)
 *   test_vectors [DIR]         make check: computes every row again and
 *                              compares it with DIR/<precision> (default:
 *                              vectors/)
 *
 * The configurations are the --impl catalog's (conformance/impl_catalog.c),
 * so that the vectors and materia-conformance --impl check the same things.
 * The rows are materia's answers through a query session (docs/PROTOCOL.md),
 * so they are exactly what materia-query answers for the same lines. Writing
 * and checking make the rows the same way: the check compares the inputs as
 * text (a change of the catalog, the points or the directions is a stale
 * file: run make vectors) and the answers as numbers, within the tolerance
 * vectors/README.md gives for this build's precision. VECTORS_VERBOSE=1 in
 * the environment prints every row that differs.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "../conformance/impl.h"
#include "materia/tools/query.h"
#include "support/check.h"

#define FORMAT_VERSION 1
#define PRECISION_NAME (MT_USE_DOUBLE ? "double" : "float")
#define PI 3.14159265358979323846

/* ---- what the vectors hold ------------------------------------------------ */
/* Shading points: every field of "at" (docs/PROTOCOL.md). 0 is the default
 * point, 1 tilts the geometric normal 37 degrees from the shading normal
 * (the light-leak rule), 2 has texture differentials, 3 a curved surface
 * (dndu, dndv) with flip set, for bump mapping. */
typedef struct vpoint {
    double p[3], n[3], ng[3], dpdu[3], dpdv[3], dndu[3], dndv[3], uv[2], dpdx[3], dpdy[3], duvdx[2], duvdy[2];
    int flip;
} vpoint;

static const vpoint points[] = {
    {{0, 0, 0}, {0, 0, 1}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}, {0, 0, 0}, {0, 0, 0}, {0.5, 0.5}, {0, 0, 0}, {0, 0, 0},
     {0, 0}, {0, 0}, 0},
    {{0, 0, 0}, {0, 0, 1}, {0.6, 0, 0.8}, {1, 0, 0}, {0, 1, 0}, {0, 0, 0}, {0, 0, 0}, {0.5, 0.5}, {0, 0, 0}, {0, 0, 0},
     {0, 0}, {0, 0}, 0},
    {{0.3, -0.2, 0.1}, {0, 0, 1}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}, {0, 0, 0}, {0, 0, 0}, {0.15, 0.7}, {0.01, 0, 0},
     {0, 0.01, 0}, {0.01, 0}, {0, 0.01}, 0},
    {{1.3, 0.4, -0.2}, {0, 0, 1}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}, {1, 0, 0}, {0, 1, 0}, {0.62, 0.41}, {0.02, 0, 0},
     {0, 0.02, 0}, {0.02, 0}, {0, 0.02}, 1},
};
#define NPOINTS ((int)(sizeof points / sizeof points[0]))
#define NBSDF_POINTS 2 /* eval, sample and rho at points 0 and 1 */

/* Directions as (cos theta, phi) about +z. */
static const double wo_dirs[][2] = {{1, 0}, {0.7, 0.7}, {0.3, 2.0}, {0.03, 3.3}, {-0.6, 4.6}};
static const double wi_dirs[][2] = {{0.95, 0.3}, {0.8, 2.2}, {0.5, 4.1},  {0.2, 5.6},
                                    {0.05, 1.1}, {-0.05, 3.0}, {-0.3, 0.5}, {-0.7, 2.6}, {-0.97, 4.9}};
#define NWO ((int)(sizeof wo_dirs / sizeof wo_dirs[0]))
#define NWI ((int)(sizeof wi_dirs / sizeof wi_dirs[0]))
#define NSAMPLES 10

/* A direction printed as the query gets it: 9 significant digits, a unit
 * vector to within 1e-8 in either precision (used as given). */
static void dir_text(char *out, size_t size, double c, double phi)
{
    double s = sqrt(1 - c * c);
    snprintf(out, size, "%.9g %.9g %.9g", s * cos(phi), s * sin(phi), c);
}

static double frac(double x) { return x - floor(x); }

/* The uniform numbers of sample i: an R3 sequence (golden-ratio-like
 * steps), away from the component boundaries k/n for n <= 8 */
static void sample_u(int i, double u[3])
{
    u[0] = frac(0.5 + 0.8191725134 * (i + 1));
    u[1] = frac(0.5 + 0.6710436067 * (i + 1));
    u[2] = frac(0.5 + 0.5497004779 * (i + 1));
}

static const char *mode_names[2] = {"pbrt-v2", "corrected"};

/* ---- a query session ------------------------------------------------------ */
static int ask(mt_query *q, const char *line, char *out, size_t size)
{
    if (mt_query_line(q, line, out, size)) return 1;
    snprintf(out, size, "error (no answer)");
    return 0;
}

static void at_line(char *out, size_t size, const vpoint *p)
{
    snprintf(out, size,
             "at p %.9g %.9g %.9g n %.9g %.9g %.9g ng %.9g %.9g %.9g dpdu %.9g %.9g %.9g dpdv %.9g %.9g %.9g "
             "dndu %.9g %.9g %.9g dndv %.9g %.9g %.9g uv %.9g %.9g dpdx %.9g %.9g %.9g dpdy %.9g %.9g %.9g "
             "duvdx %.9g %.9g duvdy %.9g %.9g flip %d",
             p->p[0], p->p[1], p->p[2], p->n[0], p->n[1], p->n[2], p->ng[0], p->ng[1], p->ng[2], p->dpdu[0],
             p->dpdu[1], p->dpdu[2], p->dpdv[0], p->dpdv[1], p->dpdv[2], p->dndu[0], p->dndu[1], p->dndu[2],
             p->dndv[0], p->dndv[1], p->dndv[2], p->uv[0], p->uv[1], p->dpdx[0], p->dpdx[1], p->dpdx[2], p->dpdy[0],
             p->dpdy[1], p->dpdy[2], p->duvdx[0], p->duvdx[1], p->duvdy[0], p->duvdy[1], p->flip);
}

/* Words as CSV fields (spaces become commas), then a comma. */
static void csv_answer_part(cf_strbuf *b, const char *ans)
{
    for (; *ans; ++ans) cf_strbuf_printf(b, "%c", *ans == ' ' ? ',' : *ans);
    cf_strbuf_printf(b, ",");
}

/* An answer as the row's last CSV fields. */
static void csv_answer(cf_strbuf *b, const char *ans)
{
    for (; *ans; ++ans) cf_strbuf_printf(b, "%c", *ans == ' ' ? ',' : *ans);
    cf_strbuf_printf(b, "\n");
}

/* A row: configuration, point, the two groups of inputs, the answer. */
static void row(cf_strbuf *b, int c, int pt, const char *in1, const char *in2, const char *ans)
{
    cf_strbuf_printf(b, "%d,%d,", c, pt);
    csv_answer_part(b, in1);
    if (in2) csv_answer_part(b, in2);
    csv_answer(b, ans);
}

/* ---- the files ------------------------------------------------------------ */
enum { F_EVAL, F_SAMPLE, F_RHO, F_BSSRDF, F_SHADING, F_TEXTURE, NFILES };
static const char *file_names[NFILES] = {"eval.csv", "sample.csv", "rho.csv", "bssrdf.csv", "shading.csv", "texture.csv"};
static const char *file_headers[NFILES] = {
    "config,point,wox,woy,woz,wix,wiy,wiz,fr,fg,fb,pdf",
    "config,point,wox,woy,woz,uc,u1,u2,wix,wiy,wiz,fr,fg,fb,pdf,flags",
    "config,point,wox,woy,woz,r,g,b",
    "config,point,has,sa_r,sa_g,sa_b,sps_r,sps_g,sps_b,eta",
    "config,point,nx,ny,nz,dpdux,dpduy,dpduz,dpdvx,dpdvy,dpdvz",
    "config,point,name,count,v0,v1,v2"};
/* leading columns that are inputs (compared as text) */
static const int file_inputs[NFILES] = {8, 8, 5, 2, 2, 3};

/* The textures a configuration's statements define, in order. */
static int texture_names(const char *scene, char names[][64], int max)
{
    int n = 0;
    const char *s = scene;
    while (n < max && (s = strstr(s, "Texture \""))) {
        const char *e;
        s += 9;
        if (!(e = strchr(s, '"')) || e - s >= 64) break;
        memcpy(names[n], s, (size_t)(e - s));
        names[n++][e - s] = 0;
        s = e + 1;
    }
    return n;
}

/* ---- the configurations: the --impl catalog (conformance/impl_catalog.c) -- */
static const cf_impl_config *catalog(int *n) { return cf_impl_configs(n); }

static int is_at(const char *line) { return !strncmp(line, "at ", 3); }

/* A configuration as the vectors give it: its statement lines joined into
 * one line (one answer, "ok"), and its own "at" lines' keys joined into one
 * (sent after each point's full "at": the configuration's uv, p or ng win
 * over the point's). "@DATA@" is replaced by data (NULL: kept). */
static void config_text(const cf_impl_config *c, const char *data, char *statements, size_t ns, char *at, size_t na)
{
    int j;
    size_t ls = 0, la = 0;
    statements[0] = at[0] = 0;
    for (j = 0; j < CI_MAX_LINES && c->lines[j]; ++j) {
        const char *l = c->lines[j];
        if (is_at(l)) {
            la += (size_t)snprintf(at + la, la < na ? na - la : 0, "%s%s", la ? " " : "", l + 3);
            continue;
        }
        if (ls && ls + 1 < ns) statements[ls++] = ' ';
        for (; *l && ls + 1 < ns; ++l) {
            if (data && !strncmp(l, "@DATA@", 6)) {
                ls += (size_t)snprintf(statements + ls, ns - ls, "%s", data);
                if (ls >= ns) ls = ns - 1;
                l += 5;
            } else {
                statements[ls++] = *l;
            }
        }
        statements[ls] = 0;
    }
}

static void write_configs(cf_strbuf *b)
{
    int i, n;
    const cf_impl_config *c = catalog(&n);
    cf_strbuf_printf(b, "id\tname\texponent\tstatements\tat\n");
    for (i = 0; i < n; ++i) {
        char st[4096], at[512];
        config_text(&c[i], NULL, st, sizeof st, at, sizeof at);
        cf_strbuf_printf(b, "%d\t%s\t%g\t%s\t%s\n", i, c[i].name, c[i].lobe_exponent, st, at);
    }
}

static void write_points(cf_strbuf *b)
{
    int i;
    cf_strbuf_printf(b, "id,px,py,pz,nx,ny,nz,ngx,ngy,ngz,dpdux,dpduy,dpduz,dpdvx,dpdvy,dpdvz,dndux,dnduy,dnduz,dndvx,dndvy,"
                 "dndvz,u,v,dpdxx,dpdxy,dpdxz,dpdyx,dpdyy,dpdyz,dudx,dvdx,dudy,dvdy,flip\n");
    for (i = 0; i < NPOINTS; ++i) {
        char at[1024], *s;
        at_line(at, sizeof at, &points[i]);
        cf_strbuf_printf(b, "%d", i);
        /* the numbers of the at line, in its order */
        for (s = at; *s;) {
            char *e;
            double v = strtod(s, &e);
            if (e != s) {
                cf_strbuf_printf(b, ",%.9g", v);
                s = e;
            } else {
                s++;
            }
        }
        cf_strbuf_printf(b, "\n");
    }
}

/* The warnings the sessions gave (a parameter a statement does not use, a
 * redefinition): a configuration that passes a parameter its material or
 * texture never reads checks nothing with it, and tells an implementation
 * that warns about it something false. Counted over every session; the
 * first one kept, named by its configuration. */
static int catalog_warnings;
static char first_warning[600];

static void on_warning(void *ctx, const char *file, int line, const char *message)
{
    (void)file;
    (void)line;
    if (!catalog_warnings++)
        snprintf(first_warning, sizeof first_warning, "%.200s: %.380s", (const char *)ctx, message);
}

/* Every row of one mode's files, through one session per configuration;
 * data is the directory of the files the statements name. 0, or -1 when a
 * session could not be made (out of memory, a configuration materia
 * refuses: the vectors would be incomplete). */
static int write_mode(int mode, const char *data, cf_strbuf files[NFILES])
{
    int c, n, f, ok = 1;
    const cf_impl_config *conf = catalog(&n);
    for (f = 0; f < NFILES; ++f) cf_strbuf_printf(&files[f], "%s\n", file_headers[f]);
    for (c = 0; c < n && ok; ++c) {
        mt_error err;
        mt_query *q = mt_query_create(NULL, &err);
        char line[1024], ans[4096], names[8][64], statements[4096], own_at[512];
        int pt, i, j, k, ntex;
        if (!q) {
            fprintf(stderr, "test_vectors: %s\n", err.message);
            return -1;
        }
        mt_query_set_warning(q, on_warning, (void *)conf[c].name);
        config_text(&conf[c], data, statements, sizeof statements, own_at, sizeof own_at);
        ntex = texture_names(statements, names, 8);
        snprintf(line, sizeof line, "mode %s", mode_names[mode]);
        ask(q, line, ans, sizeof ans);
        ask(q, statements, ans, sizeof ans);
        if (strcmp(ans, "ok")) {
            fprintf(stderr, "test_vectors: %s: %s\n", conf[c].name, ans);
            ok = 0;
        }
        for (pt = 0; pt < NPOINTS && ok; ++pt) {
            at_line(line, sizeof line, &points[pt]);
            ask(q, line, ans, sizeof ans);
            if (own_at[0]) {
                snprintf(line, sizeof line, "at %s", own_at);
                ask(q, line, ans, sizeof ans);
                if (strcmp(ans, "ok")) {
                    fprintf(stderr, "test_vectors: %s: %s: %s\n", conf[c].name, line, ans);
                    ok = 0;
                }
            }
            if (pt < NBSDF_POINTS)
                for (i = 0; i < NWO; ++i) {
                    char wo[96];
                    double ct = wo_dirs[i][0], st = sqrt(1 - ct * ct), ph = wo_dirs[i][1];
                    dir_text(wo, sizeof wo, ct, ph);
                    /* the fixed directions, the mirror direction (the glossy
                     * peak) and its opposite (a BTDF's peak) */
                    for (j = 0; j < NWI + 2; ++j) {
                        char wi[96];
                        if (j < NWI)
                            dir_text(wi, sizeof wi, wi_dirs[j][0], wi_dirs[j][1]);
                        else
                            snprintf(wi, sizeof wi, "%.9g %.9g %.9g", -st * cos(ph), -st * sin(ph),
                                     j == NWI ? ct : -ct);
                        snprintf(line, sizeof line, "eval %s %s", wo, wi);
                        ask(q, line, ans, sizeof ans);
                        row(&files[F_EVAL], c, pt, wo, wi, ans);
                    }
                    for (k = 0; k < NSAMPLES; ++k) {
                        double u[3];
                        char us[64];
                        sample_u(k + NSAMPLES * i, u);
                        snprintf(us, sizeof us, "%.9g %.9g %.9g", u[0], u[1], u[2]);
                        snprintf(line, sizeof line, "sample %s %s", wo, us);
                        ask(q, line, ans, sizeof ans);
                        row(&files[F_SAMPLE], c, pt, wo, us, ans);
                    }
                    /* rho (adaptive cubature, the slow query) at point 0 for
                     * normal incidence and cos theta 0.3 */
                    if (pt == 0 && (i == 0 || i == 2)) {
                        snprintf(line, sizeof line, "rho %s", wo);
                        ask(q, line, ans, sizeof ans);
                        row(&files[F_RHO], c, pt, wo, NULL, ans);
                    }
                }
            ask(q, "bssrdf", ans, sizeof ans);
            cf_strbuf_printf(&files[F_BSSRDF], "%d,%d,", c, pt);
            if (!strcmp(ans, "none"))
                cf_strbuf_printf(&files[F_BSSRDF], "0,,,,,,,\n");
            else {
                cf_strbuf_printf(&files[F_BSSRDF], "1,");
                csv_answer(&files[F_BSSRDF], ans);
            }
            ask(q, "shading", ans, sizeof ans);
            cf_strbuf_printf(&files[F_SHADING], "%d,%d,", c, pt);
            csv_answer(&files[F_SHADING], ans);
            for (k = 0; k < ntex; ++k) {
                int count = 1;
                const char *s;
                snprintf(line, sizeof line, "texture \"%s\"", names[k]);
                ask(q, line, ans, sizeof ans);
                for (s = ans; *s; ++s) count += *s == ' ';
                cf_strbuf_printf(&files[F_TEXTURE], "%d,%d,%s,%d,", c, pt, names[k], count);
                if (count == 1) cf_strbuf_printf(&files[F_TEXTURE], "%s,,\n", ans);
                else csv_answer(&files[F_TEXTURE], ans);
            }
        }
        mt_query_destroy(q);
    }
    for (f = 0; f < NFILES; ++f)
        if (files[f].failed) {
            fprintf(stderr, "test_vectors: out of memory for %s\n", file_names[f]);
            ok = 0;
        }
    return ok ? 0 : -1;
}

/* ---- the data files (@DATA@) ------------------------------------------------ */
/* The files the catalog names, written by the suite (cf_impl_write_data):
 * the spectra are small and published in vectors/data/; the MERL table
 * (35 MB) is not, materia-conformance --write-data DIR writes it. */
static const char *const data_files[] = {"eta.spd", "k.spd", "plastic.merl"};
#define NDATA_PUBLISHED 2

static int make_data(char *dir, size_t n)
{
    char msg[512];
    const char *tmp = getenv("TMPDIR");
    snprintf(dir, n, "%s/test_vectors-XXXXXX", tmp && *tmp ? tmp : "/tmp");
    if (!mkdtemp(dir)) {
        fprintf(stderr, "test_vectors: cannot make %s: %s\n", dir, strerror(errno));
        return -1;
    }
    if (cf_impl_write_data(dir, msg, sizeof msg)) {
        fprintf(stderr, "test_vectors: %s\n", msg);
        return -1;
    }
    return 0;
}

static void remove_data(const char *dir)
{
    char p[4200];
    size_t i;
    for (i = 0; i < sizeof data_files / sizeof data_files[0]; ++i) {
        snprintf(p, sizeof p, "%s/%s", dir, data_files[i]);
        remove(p);
    }
    rmdir(dir);
}

static void write_version(cf_strbuf *b)
{
    cf_strbuf_printf(b, "format %d\nmateria %s\nprotocol %d\nprecision %s\nmodes pbrt-v2 corrected\n", FORMAT_VERSION,
              MT_VERSION, MT_QUERY_PROTOCOL_VERSION, PRECISION_NAME);
}

/* ---- writing ---------------------------------------------------------------- */
static int write_file(const char *dir, const char *sub, const char *name, const cf_strbuf *b)
{
    char path[2048], tmp[2100];
    FILE *f;
    snprintf(path, sizeof path, "%s/%s%s%s", dir, sub, *sub ? "/" : "", name);
    snprintf(tmp, sizeof tmp, "%s.tmp", path);
    if (b->failed) {
        fprintf(stderr, "test_vectors: out of memory for %s\n", path);
        return 0;
    }
    if (!(f = fopen(tmp, "wb")) || fwrite(b->s, 1, b->n, f) != b->n || fclose(f) != 0 || rename(tmp, path) != 0) {
        fprintf(stderr, "test_vectors: cannot write %s: %s\n", path, strerror(errno));
        return 0;
    }
    return 1;
}

static int make_dir(const char *dir, const char *sub)
{
    char path[2048];
    snprintf(path, sizeof path, "%s%s%s", dir, *sub ? "/" : "", sub);
    if (mkdir(path, 0777) != 0 && errno != EEXIST) {
        fprintf(stderr, "test_vectors: cannot create %s: %s\n", path, strerror(errno));
        return 0;
    }
    return 1;
}

static char *read_all(const char *path);

/* The published data file name of dir (the generated data directory) as
 * a buffer; 0 when it cannot be read. */
static int data_text(const char *data, const char *name, cf_strbuf *b)
{
    char path[4200];
    char *text;
    snprintf(path, sizeof path, "%s/%s", data, name);
    if (!(text = read_all(path))) return 0;
    cf_strbuf_clear(b);
    cf_strbuf_printf(b, "%s", text);
    free(text);
    return !b->failed;
}

/* Writes dir/configs.tsv, dir/points.csv, dir/data/ (the published data
 * files; the same from either precision) and dir/PRECISION/: VERSION and a
 * directory of CSV files per mode. */
static int write_all(const char *dir)
{
    cf_strbuf b = {0, 0, 0, 0};
    char pdir[1024], data[1024];
    int m, f, ok = make_dir(dir, "");
    if (make_data(data, sizeof data)) return 0;
    snprintf(pdir, sizeof pdir, "%s/%s", dir, PRECISION_NAME);
    ok = ok && make_dir(pdir, "") && make_dir(dir, "data");
    write_version(&b);
    ok = ok && write_file(pdir, "", "VERSION", &b);
    cf_strbuf_clear(&b);
    write_configs(&b);
    ok = ok && write_file(dir, "", "configs.tsv", &b);
    cf_strbuf_clear(&b);
    write_points(&b);
    ok = ok && write_file(dir, "", "points.csv", &b);
    for (f = 0; f < NDATA_PUBLISHED; ++f) ok = ok && data_text(data, data_files[f], &b) && write_file(dir, "data", data_files[f], &b);
    cf_strbuf_free(&b);
    for (m = 0; m < 2 && ok; ++m) {
        cf_strbuf files[NFILES];
        memset(files, 0, sizeof files);
        ok = !write_mode(m, data, files) && make_dir(pdir, mode_names[m]);
        if (catalog_warnings) {
            fprintf(stderr, "test_vectors: the catalog's statements gave %d warnings; the first: %s\n", catalog_warnings,
                    first_warning);
            ok = 0;
        }
        for (f = 0; f < NFILES; ++f) {
            ok = ok && write_file(pdir, mode_names[m], file_names[f], &files[f]);
            cf_strbuf_free(&files[f]);
        }
    }
    remove_data(data);
    return ok;
}

/* ---- checking --------------------------------------------------------------- */
static char *read_all(const char *path)
{
    FILE *f = fopen(path, "rb");
    char *s;
    long n;
    if (!f) return NULL;
    if (fseek(f, 0, SEEK_END) != 0 || (n = ftell(f)) < 0 || fseek(f, 0, SEEK_SET) != 0 ||
        !(s = malloc((size_t)n + 1))) {
        fclose(f);
        return NULL;
    }
    if (fread(s, 1, (size_t)n, f) != (size_t)n) {
        fclose(f);
        free(s);
        return NULL;
    }
    s[n] = 0;
    fclose(f);
    return s;
}

/* The tolerance of vectors/README.md for the build that wrote the
 * vectors of its precision: a few units in the last place (another
 * compiler, or libm's code path on another processor, may round
 * differently), relative to the value or to 1e-3 of the row's largest
 * answer. The configuration's lobe exponent e is not needed within one
 * precision. */
static double tolerance(double exponent)
{
    (void)exponent;
#if MT_USE_DOUBLE
    return 1e-12;
#else
    return 1e-6;
#endif
}

typedef struct worst {
    double err;
    int line;
    char got[512], want[512];
} worst;

/* Compares one file's generated text with the published one. */
static void check_text(const char *name, const char *got, const char *want, int inputs, const double *exponents,
                       int nconf, double min_tol)
{
    int line = 1, bad_inputs = 0, bad_values = 0, rows = 0;
    worst w = {0, 0, "", ""};
    const char *g = got, *p = want;
    char tname[200];
    snprintf(tname, sizeof tname, "vectors %s", name);
    while (*g && *p) {
        const char *ge = strchr(g, '\n'), *pe = strchr(p, '\n');
        size_t gl = ge ? (size_t)(ge - g) : strlen(g), pl = pe ? (size_t)(pe - p) : strlen(p);
        if (inputs < 0 || line == 1) {
            if (gl != pl || memcmp(g, p, gl)) bad_inputs++;
        } else {
            /* field by field */
            const char *a = g, *b = p;
            int field = 0, cfg = atoi(g);
            double tol = fmax(min_tol, tolerance(cfg >= 0 && cfg < nconf ? exponents[cfg] : 0)), scale = 0, err = 0;
            const char *ga = g, *pa = p;
            /* the row's scale: its largest answer, so that a value that is
             * zero in one build and a rounding error in the other passes */
            for (field = 0; pa < p + pl; ++field) {
                char *e;
                double v = strtod(pa, &e);
                if (field >= inputs && e != pa) scale = fmax(scale, fabs(v));
                pa = memchr(pa, ',', (size_t)(p + pl - pa));
                if (!pa) break;
                pa++;
            }
            (void)ga;
            for (field = 0;; ++field) {
                const char *ae = memchr(a, ',', (size_t)(g + gl - a)), *be = memchr(b, ',', (size_t)(p + pl - b));
                size_t al = ae ? (size_t)(ae - a) : (size_t)(g + gl - a), bl = be ? (size_t)(be - b) : (size_t)(p + pl - b);
                if (field < inputs || al == 0 || bl == 0) {
                    if (al != bl || memcmp(a, b, al)) {
                        if (getenv("VECTORS_VERBOSE")) printf("  line %d field %d: %.*s | %.*s\n", line, field, (int)al, a, (int)bl, b);
                        if (field < inputs) bad_inputs++;
                        else err = INFINITY;
                        if (field < inputs) break;
                    }
                } else {
                    char *e1, *e2;
                    double x = strtod(a, &e1), y = strtod(b, &e2);
                    if (e1 != a + al || e2 != b + bl) {
                        if (al != bl || memcmp(a, b, al)) err = INFINITY;
                    } else {
                        double d = fabs(x - y) / fmax(fmax(fabs(y), 1e-3 * scale), 1e-30);
                        if (!(d <= err)) err = d;
                    }
                }
                if (!ae || !be) {
                    if (ae || be) err = INFINITY;
                    break;
                }
                a = ae + 1;
                b = be + 1;
            }
            rows++;
            if (err > w.err) {
                w.err = err;
                w.line = line;
                snprintf(w.got, sizeof w.got, "%.*s", (int)gl, g);
                snprintf(w.want, sizeof w.want, "%.*s", (int)pl, p);
            }
            if (!(err <= tol)) {
                bad_values++;
                if (getenv("VECTORS_VERBOSE"))
                    printf("  line %d err %.3g tol %.3g\n    %.*s\n    %.*s\n", line, err, tol, (int)gl, g, (int)pl, p);
            }
        }
        g = ge ? ge + 1 : g + gl;
        p = pe ? pe + 1 : p + pl;
        line++;
    }
    if (*g || *p) bad_inputs++;
    if (bad_inputs) {
        t_fail(tname, "stale: rows or inputs differ from what the catalog gives now (line %d); run make vectors", line);
        return;
    }
    if (bad_values)
        t_fail(tname, "%d of %d rows differ beyond the tolerance; worst (relative %.3g) line %d:\n  computed  %s\n  published %s",
               bad_values, rows, w.err, w.line, w.got, w.want);
    else if (inputs >= 0)
        printf("PASS %s: %d rows, worst relative difference %.3g (line %d)\n", tname, rows, w.err, w.line);
    else
        t_pass(tname);
}

static void check_file(const char *dir, const char *sub, const char *name, const cf_strbuf *b, int inputs,
                       const double *exponents, int nconf)
{
    char path[1024], label[160];
    char *want;
    snprintf(path, sizeof path, "%s/%s%s%s", dir, sub, *sub ? "/" : "", name);
    snprintf(label, sizeof label, "%s%s%s", sub, *sub ? "/" : "", name);
    if (b->failed) {
        t_fail("vectors", "out of memory computing %s", label);
        return;
    }
    if (!(want = read_all(path))) {
        t_fail("vectors", "cannot read %s (run make vectors)", path);
        return;
    }
    /* rho is adaptive cubature to 1e-6: a last-bit change can move its
     * subdivision, and the result by up to its tolerance */
    check_text(label, b->s ? b->s : "", want, inputs, exponents, nconf, strstr(name, "rho") ? 3e-6 : 0);
    free(want);
}

static void check_all(const char *dir)
{
    cf_strbuf b = {0, 0, 0, 0};
    int m, f, n, i;
    const cf_impl_config *c = catalog(&n);
    double *ex = malloc(sizeof *ex * (size_t)(n ? n : 1));
    char *version, path[1024], data[1024];
    if (!ex || make_data(data, sizeof data)) {
        t_fail("vectors", "cannot write the data files the configurations name");
        free(ex);
        return;
    }
    for (i = 0; i < n; ++i) ex[i] = c[i].lobe_exponent;
    /* the VERSION file names the producer: only its format and materia's
     * version must match */
    snprintf(path, sizeof path, "%s/%s/VERSION", dir, PRECISION_NAME);
    version = read_all(path);
    if (!version)
        t_fail("vectors VERSION", "cannot read %s (run make vectors)", path);
    else {
        char want[128];
        snprintf(want, sizeof want, "format %d\nmateria %s\nprotocol %d\nprecision %s\n", FORMAT_VERSION, MT_VERSION,
                 MT_QUERY_PROTOCOL_VERSION, PRECISION_NAME);
        t_check(!strncmp(version, want, strlen(want)), "vectors VERSION: format, materia version, protocol, precision",
                "%s says\n%s", path, version);
    }
    free(version);
    write_configs(&b);
    check_file(dir, "", "configs.tsv", &b, -1, ex, n);
    cf_strbuf_clear(&b);
    write_points(&b);
    check_file(dir, "", "points.csv", &b, -1, ex, n);
    for (f = 0; f < NDATA_PUBLISHED; ++f) {
        if (data_text(data, data_files[f], &b))
            check_file(dir, "data", data_files[f], &b, -1, ex, n);
        else
            t_fail("vectors data", "cannot read the %s just written in %s", data_files[f], data);
    }
    cf_strbuf_free(&b);
    for (m = 0; m < 2; ++m) {
        cf_strbuf files[NFILES];
        char sub[64], label[160];
        memset(files, 0, sizeof files);
        catalog_warnings = 0;
        if (write_mode(m, data, files)) t_fail("vectors", "%s: the queries could not all be made", mode_names[m]);
        snprintf(label, sizeof label, "catalog, %s mode: every parameter of every statement is used", mode_names[m]);
        t_check(!catalog_warnings, label, "%d warnings; the first: %s", catalog_warnings, first_warning);
        snprintf(sub, sizeof sub, "%s/%s", PRECISION_NAME, mode_names[m]);
        for (f = 0; f < NFILES; ++f) {
            check_file(dir, sub, file_names[f], &files[f], file_inputs[f], ex, n);
            cf_strbuf_free(&files[f]);
        }
    }
    remove_data(data);
    free(ex);
}

int main(int argc, char **argv)
{
    if (argc == 3 && !strcmp(argv[1], "--write")) {
        return write_all(argv[2]) ? 0 : 1;
    }
    if (argc > 2 || (argc == 2 && argv[1][0] == '-')) {
        fprintf(stderr, "usage: %s [--write DIR | DIR]\n", argv[0]);
        return 2;
    }
    check_all(argc == 2 ? argv[1] : "vectors");
    return t_status();
}
