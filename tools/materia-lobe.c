/*
 * materia-lobe: a picture of a material's scattering at one incident
 * direction, from materia itself or from any program that speaks the query
 * protocol (docs/PROTOCOL.md).
 *
 *   materia-lobe [--impl 'COMMAND'] [--against 'COMMAND'] [--mode M]
 *                [--samples N] [--timeout S] [--raw PREFIX]
 *                --wo THETA PHI -o lobe.png STATEMENTS...
 *
 * One row per implementation (A: --impl, or materia in-process; B:
 * --against), and with B a third row A - B. Each row has four panels:
 * f cos over the whole sphere, the pdf, a histogram of N samples (as a
 * density, on the pdf's scale), each a lat-long map, and a polar plot of
 * f cos (white) and the pdf (cyan) in the plane of incidence, with wo in
 * yellow; the layout is lobe.h. Each panel has a colour bar with its range.
 * f is the mean of f's three channels; the directions are world space at
 * the protocol's default shading point (normal +z).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "image/font.h"
#include "image/heatcolour.h"
#include "materia.h"
#include "materia/tools/query.h"
#include "lobe.h"
#include "protochild.h"
#include "toolargs.h"

#define POLAR_N 721
#define BATCH 256
#define ANS 512
#define PI 3.14159265358979323846

/* ---- an implementation: materia in-process or a child ------------------- */
typedef struct impl {
    const char *label;
    mt_query *q;    /* in-process, or NULL */
    pc_child child; /* otherwise */
} impl;

static const char *prog = "materia-lobe";

static void die(const char *fmt, const char *a, const char *b)
{
    fprintf(stderr, "%s: ", prog);
    fprintf(stderr, fmt, a, b);
    fprintf(stderr, "\n");
    exit(1);
}

/* Sends n lines (each a query or a statement that is answered), reads n
 * answers. */
static void ask(impl *m, char (*lines)[160], int n, char (*answers)[ANS])
{
    int i, j;
    char err[256];
    for (i = 0; i < n; i += BATCH) {
        int k = n - i < BATCH ? n - i : BATCH;
        if (m->q) {
            for (j = 0; j < k; ++j)
                if (!mt_query_line(m->q, lines[i + j], answers[i + j], ANS)) answers[i + j][0] = 0;
            continue;
        }
        {
            static char text[BATCH * 161];
            size_t len = 0;
            for (j = 0; j < k; ++j) {
                size_t l = strlen(lines[i + j]);
                memcpy(text + len, lines[i + j], l);
                text[len + l] = '\n';
                len += l + 1;
            }
            if (!pc_write(&m->child, text, len, err, sizeof err)) die("%s: %s", m->label, err);
        }
        for (j = 0; j < k; ++j)
            if (!pc_read_line(&m->child, answers[i + j], ANS, err, sizeof err)) {
                fprintf(stderr, "%s: %s: query \"%s\": %s\n", prog, m->label, lines[i + j], err);
                exit(1);
            }
    }
}

/* The numbers of an answer; exits naming the query when there are fewer
 * than n or one is not finite. */
static void parse(const impl *m, const char *line, const char *answer, double *v, int n)
{
    const char *s = answer;
    int i;
    for (i = 0; i < n; ++i) {
        char *e;
        v[i] = strtod(s, &e);
        if (e == s || !isfinite(v[i])) {
            fprintf(stderr, "%s: %s: query \"%s\" answered \"%s\" (wanted %d numbers)\n", prog, m->label, line, answer, n);
            exit(1);
        }
        s = e;
    }
}

/* ---- what is drawn ---------------------------------------------------------- */
typedef struct lobe {
    float fcos[LL_H][LL_W], pdf[LL_H][LL_W], hist[LL_H][LL_W];
    double polar_f[POLAR_N], polar_pdf[POLAR_N];
    long failed;
} lobe;

static void ll_dir(int x, int y, double *w)
{
    double phi = 2 * PI * (x + 0.5) / LL_W, th = PI * (y + 0.5) / LL_H;
    w[0] = sin(th) * cos(phi);
    w[1] = sin(th) * sin(phi);
    w[2] = cos(th);
}

/* The direction at angle a (radians, -pi..pi) from +z in the plane of
 * incidence: a > 0 towards wo's azimuth. */
static void plane_dir(double a, double phi_o, double *w)
{
    w[0] = sin(a) * cos(phi_o);
    w[1] = sin(a) * sin(phi_o);
    w[2] = cos(a);
}

static void measure(impl *m, const char *mode, const char *statements, const double *wo, double phi_o, long samples,
                    lobe *L)
{
    /* static: an error exits from anywhere, and nothing is left allocated */
    static char lines[BATCH * 8][160], ans[BATCH * 8][ANS], setup[2][160], setup_ans[2][ANS];
    int n = LL_W * LL_H, i, x, y;
    mt_rng rng;
    long k;
    snprintf(setup[0], sizeof setup[0], "mode %s", mode);
    ask(m, setup, 1, setup_ans);
    if (strcmp(setup_ans[0], "ok")) die("%s: mode: %s", m->label, setup_ans[0]);
    if (m->q) {
        char a[4096];
        if (!mt_query_line(m->q, statements, a, sizeof a)) snprintf(a, sizeof a, "no answer (unclosed statement)");
        if (strcmp(a, "ok")) die("the statements: %s%s", a, "");
    } else {
        char err[256], a[ANS];
        if (!pc_write(&m->child, statements, strlen(statements), err, sizeof err) ||
            !pc_write(&m->child, "\n", 1, err, sizeof err) || !pc_read_line(&m->child, a, sizeof a, err, sizeof err))
            die("%s: %s", m->label, err);
        if (strcmp(a, "ok")) die("%s: the statements: %s", m->label, a);
    }
    /* the sphere, BATCH * 8 queries at a time */
    for (i = 0; i < n; i += BATCH * 8) {
        int j, c = n - i < BATCH * 8 ? n - i : BATCH * 8;
        for (j = 0; j < c; ++j) {
            double wi[3];
            ll_dir((i + j) % LL_W, (i + j) / LL_W, wi);
            snprintf(lines[j], sizeof lines[j], "eval %.9g %.9g %.9g %.9g %.9g %.9g", wo[0], wo[1], wo[2], wi[0], wi[1],
                     wi[2]);
        }
        ask(m, lines, c, ans);
        for (j = 0; j < c; ++j) {
            double v[4], wi[3];
            x = (i + j) % LL_W;
            y = (i + j) / LL_W;
            ll_dir(x, y, wi);
            parse(m, lines[j], ans[j], v, 4);
            L->fcos[y][x] = (float)((v[0] + v[1] + v[2]) / 3 * fabs(wi[2]));
            L->pdf[y][x] = (float)v[3];
        }
    }
    /* the plane of incidence */
    for (i = 0; i < POLAR_N; ++i) {
        double wi[3];
        plane_dir(-PI + 2 * PI * i / (POLAR_N - 1), phi_o, wi);
        snprintf(lines[i], sizeof lines[i], "eval %.9g %.9g %.9g %.9g %.9g %.9g", wo[0], wo[1], wo[2], wi[0], wi[1], wi[2]);
    }
    ask(m, lines, POLAR_N, ans);
    for (i = 0; i < POLAR_N; ++i) {
        double v[4], wi[3];
        plane_dir(-PI + 2 * PI * i / (POLAR_N - 1), phi_o, wi);
        parse(m, lines[i], ans[i], v, 4);
        L->polar_f[i] = (v[0] + v[1] + v[2]) / 3 * fabs(wi[2]);
        L->polar_pdf[i] = v[3];
    }
    /* samples: the same uniform numbers for every implementation, printed
     * so that they read back exactly */
    memset(L->hist, 0, sizeof L->hist);
    L->failed = 0;
    mt_rng_seed(&rng, 1, 7);
    for (k = 0; k < samples; k += BATCH * 8) {
        int j, c = samples - k < BATCH * 8 ? (int)(samples - k) : BATCH * 8;
        for (j = 0; j < c; ++j) {
            float u0 = (float)mt_rng_uniform_d(&rng), u1 = (float)mt_rng_uniform_d(&rng), u2 = (float)mt_rng_uniform_d(&rng);
            if (u0 >= 1) u0 = 0x1.fffffep-1f;
            if (u1 >= 1) u1 = 0x1.fffffep-1f;
            if (u2 >= 1) u2 = 0x1.fffffep-1f;
            snprintf(lines[j], sizeof lines[j], "sample %.9g %.9g %.9g %.9g %.9g %.9g", wo[0], wo[1], wo[2], u0, u1, u2);
        }
        ask(m, lines, c, ans);
        for (j = 0; j < c; ++j) {
            double v[8], th, ph;
            parse(m, lines[j], ans[j], v, 8);
            if (!(v[6] > 0)) {
                L->failed++;
                continue;
            }
            th = acos(fmax(-1, fmin(1, v[2] / sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]))));
            ph = atan2(v[1], v[0]);
            if (ph < 0) ph += 2 * PI;
            x = (int)(ph / (2 * PI) * LL_W);
            y = (int)(th / PI * LL_H);
            L->hist[y < LL_H ? y : LL_H - 1][x < LL_W ? x : LL_W - 1] += 1;
        }
    }
    /* counts to a density per steradian, comparable with the pdf */
    for (y = 0; y < LL_H; ++y) {
        double dw = 2 * PI / LL_W * (cos(PI * y / LL_H) - cos(PI * (y + 1) / LL_H));
        for (x = 0; x < LL_W; ++x) L->hist[y][x] = (float)(L->hist[y][x] / ((double)(samples > 0 ? samples : 1) * dw));
    }
}

/* ---- drawing ------------------------------------------------------------------ */
static const float white[3] = {1, 1, 1}, grey[3] = {0.35f, 0.35f, 0.35f}, cyan[3] = {0.1f, 0.8f, 1},
                   yellow[3] = {1, 0.85f, 0.1f};

static void put(mt_image *img, int x, int y, const float *rgb)
{
    float *p;
    if (x < 0 || y < 0 || x >= img->width || y >= img->height) return;
    p = img->data + ((size_t)y * (size_t)img->width + (size_t)x) * 3;
    p[0] = rgb[0], p[1] = rgb[1], p[2] = rgb[2];
}

/* signed values: blue (negative), black, red (positive) */
static void signed_colour(double t, float *rgb)
{
    if (!(t == t)) t = 1;
    t = t < -1 ? -1 : t > 1 ? 1 : t;
    rgb[0] = (float)(t > 0 ? t : 0);
    rgb[1] = (float)(fabs(t) * 0.15);
    rgb[2] = (float)(t < 0 ? -t : 0);
}

static void colour_of(double v, double lo, double hi, int is_signed, float *rgb)
{
    if (!isfinite(v)) {
        rgb[0] = 1, rgb[1] = 0, rgb[2] = 1; /* magenta: a bug in the implementation */
        return;
    }
    if (is_signed)
        signed_colour(hi > 0 ? v / hi : 0, rgb);
    else
        mt__heat_colour(hi > lo ? (v - lo) / (hi - lo) : 0, rgb);
}

/* The bar under a panel at (x0, y0) of width w: the scale from lo to hi. */
static void draw_bar(mt_image *img, int x0, int y0, int w, double lo, double hi, int is_signed)
{
    char s[32];
    int x, y;
    for (x = 0; x < w; ++x) {
        float rgb[3];
        double t = w > 1 ? (double)x / (w - 1) : 1;
        colour_of(is_signed ? -hi + 2 * hi * t : lo + (hi - lo) * t, lo, hi, is_signed, rgb);
        for (y = y0 + 2; y < y0 + 8; ++y) put(img, x0 + x, y, rgb);
    }
    snprintf(s, sizeof s, "%.3g", is_signed ? -hi : lo);
    mt__draw_text(img, x0, y0 + 10, s, 1, white);
    snprintf(s, sizeof s, "%.3g", hi);
    mt__draw_text(img, x0 + w - mt__text_width(s, 1), y0 + 10, s, 1, white);
}

static double map_max(float (*m)[LL_W], int absolute)
{
    double v = 0;
    int x, y;
    for (y = 0; y < LL_H; ++y)
        for (x = 0; x < LL_W; ++x)
            if (isfinite(m[y][x])) v = fmax(v, absolute ? fabs(m[y][x]) : m[y][x]);
    return v;
}

static void draw_map(mt_image *img, int x0, int y0, float (*m)[LL_W], double hi, int is_signed, const char *title)
{
    int x, y;
    mt__draw_text(img, x0, y0 - TITLE + 1, title, 1, white);
    for (y = 0; y < LL_H; ++y)
        for (x = 0; x < LL_W; ++x) {
            float rgb[3];
            colour_of(m[y][x], 0, hi, is_signed, rgb);
            put(img, x0 + x, y0 + y, rgb);
        }
    /* the horizon */
    for (x = 0; x < LL_W; x += 4) put(img, x0 + x, y0 + LL_H / 2, grey);
    draw_bar(img, x0, y0 + LL_H, LL_W, 0, hi, is_signed);
}

static void draw_curve(mt_image *img, int cx, int cy, int r, const double *v, double hi, const float *rgb)
{
    int i;
    for (i = 0; i < POLAR_N; ++i) {
        double a = -PI + 2 * PI * i / (POLAR_N - 1), t = hi > 0 ? fabs(v[i]) / hi : 0;
        int k;
        /* a line from the previous point to this one */
        for (k = 0; k <= 8; ++k) {
            double b = i ? a - 2 * PI / (POLAR_N - 1) * (1 - k / 8.0) : a,
                   s = i ? (fabs(v[i - 1]) + (fabs(v[i]) - fabs(v[i - 1])) * k / 8.0) / (hi > 0 ? hi : 1) : t;
            if (!isfinite(s)) continue;
            put(img, cx + (int)lround(r * s * sin(b)), cy - (int)lround(r * s * cos(b)), rgb);
        }
    }
}

static void draw_polar(mt_image *img, int x0, int y0, const double *f, const double *pdf, double theta_o, int diff)
{
    int r = LL_H / 2 - 2, cx = x0 + LL_H / 2, cy = y0 + LL_H / 2, i;
    double hf = 0, hp = 0;
    char s[64];
    for (i = 0; i < POLAR_N; ++i) {
        if (isfinite(f[i])) hf = fmax(hf, fabs(f[i]));
        if (isfinite(pdf[i])) hp = fmax(hp, fabs(pdf[i]));
    }
    mt__draw_text(img, x0, y0 - TITLE + 1, diff ? "plane |A-B|" : "plane of incidence", 1, white);
    for (i = -r; i <= r; ++i) put(img, cx + i, cy, grey); /* the surface */
    for (i = 0; i <= r; ++i) put(img, cx + (int)lround(i * sin(theta_o)), cy - (int)lround(i * cos(theta_o)), yellow);
    draw_curve(img, cx, cy, r, pdf, hp, cyan);
    draw_curve(img, cx, cy, r, f, hf, white);
    snprintf(s, sizeof s, "f cos %.3g", hf);
    mt__draw_text(img, x0, y0 + LL_H + 2, s, 1, white);
    snprintf(s, sizeof s, "pdf %.3g", hp);
    mt__draw_text(img, x0, y0 + LL_H + 11, s, 1, cyan);
}

static int write_raw(const char *prefix, const char *row, const char *what, float (*m)[LL_W])
{
    char path[1024];
    mt_image img;
    mt_error err;
    int x, y;
    snprintf(path, sizeof path, "%s-%s-%s.pfm", prefix, row, what);
    if (mt_image_create(&img, LL_W, LL_H, 1, &err)) return 0;
    for (y = 0; y < LL_H; ++y)
        for (x = 0; x < LL_W; ++x) img.data[y * LL_W + x] = m[y][x];
    if (mt_image_write(path, &img, NULL, 0, &err)) {
        fprintf(stderr, "%s: %s\n", prog, err.message);
        mt_image_destroy(&img);
        return 0;
    }
    mt_image_destroy(&img);
    return 1;
}

static void usage(FILE *f)
{
    fprintf(f,
            "usage: %s [--impl 'COMMAND'] [--against 'COMMAND'] [--mode pbrt-v2|corrected] [--samples N]\n"
            "       [--timeout SECONDS] [--raw PREFIX] --wo THETA PHI -o lobe.png STATEMENTS...\n"
            "       %s --help | --version\n",
            prog, prog);
}

/* --help: every option with its default, and the exit statuses */
static void help(void)
{
    usage(stdout);
    fputs("A picture of a material's scattering at one incident direction: f cos and the pdf over the\n"
          "whole sphere, a histogram of sampled directions on the pdf's scale, and a polar plot of the\n"
          "plane of incidence. The statements (pbrt-v2 scene text, the arguments joined with spaces,\n"
          "on one line) make the material, as in a query session (docs/PROTOCOL.md).\n"
          "  --wo THETA PHI      the incident direction, in degrees: THETA 0 to 180 from the normal\n"
          "                      (+z), PHI -360 to 360 (required)\n"
          "  -o FILE.png         the picture (required); written to a temporary file and renamed\n"
          "  --impl 'COMMAND'    draw this program's answers (any program speaking the query\n"
          "                      protocol) instead of materia's (default: materia, in-process)\n"
          "  --against 'COMMAND' a second row from this program and a third with their difference\n"
          "                      (default: none)\n"
          "  --mode M            corrected (the default) or pbrt-v2. corrected, as materia-conformance\n"
          "                      --impl: a renderer is compared with the physics; every other tool,\n"
          "                      and the library, default to pbrt-v2\n"
          "  --samples N         samples for the histogram, 0 to 1e8 (default 200000; 0: no samples\n"
          "                      drawn, the histogram panels stay empty)\n"
          "  --timeout SECONDS   the longest wait for a child's answer, 1 to 3600 (default 30)\n"
          "  --raw PREFIX        also each map as PFM: PREFIX-ROW-WHAT.pfm (default: none)\n"
          "  --help, -h          this text;  --version  materia's version and precision\n"
          "Exit status: 0 drawn and written, 1 error (a child that fails or answers wrongly, an\n"
          "unwritable output: the message on standard error, nothing written), 2 wrong command line.\n",
          stdout);
}

int main(int argc, char **argv)
{
    const char *impl_cmd = NULL, *against = NULL, *mode = "corrected", *out = NULL, *raw = NULL;
    double theta = -1, phi = 0, v, wo[3], timeout = 30;
    long samples = 200000;
    static char *statements; /* static, as m: reachable when an error exits */
    size_t len = 1;
    int i, first = 0, nimpl, rows, r, lines_stmt, width, height, per_line;
    static impl m[2];
    static lobe L[3];
    mt_image img;
    mt_error err;
    char header[4][256];
    for (i = 1; i < argc && !first; ++i) {
        const char *a = argv[i];
        if ((i + 1 == argc && (!strcmp(a, "--impl") || !strcmp(a, "--against") || !strcmp(a, "--mode") ||
                               !strcmp(a, "--samples") || !strcmp(a, "--timeout") || !strcmp(a, "--raw") ||
                               !strcmp(a, "-o"))) ||
            (i + 2 >= argc && !strcmp(a, "--wo"))) {
            if (strcmp(a, "--wo")) return tool_no_value(prog, a);
            fprintf(stderr, "%s: --wo needs two values, THETA PHI\n", prog);
            return 2;
        }
        if (!strcmp(a, "--impl") && i + 1 < argc)
            impl_cmd = argv[++i];
        else if (!strcmp(a, "--against") && i + 1 < argc)
            against = argv[++i];
        else if (!strcmp(a, "--mode") && i + 1 < argc) {
            mode = argv[++i];
            if (strcmp(mode, "pbrt-v2") && strcmp(mode, "corrected")) {
                fprintf(stderr, "%s: --mode is pbrt-v2 or corrected, not \"%s\"\n", prog, mode);
                return 2;
            }
        } else if (!strcmp(a, "--samples") && i + 1 < argc) {
            if (!tool_number(prog, "--samples", argv[++i], 0, 1e8, 1, &v)) return 2;
            samples = (long)v;
        } else if (!strcmp(a, "--timeout") && i + 1 < argc) {
            if (!tool_number(prog, "--timeout", argv[++i], 1, 3600, 0, &timeout)) return 2;
        } else if (!strcmp(a, "--raw") && i + 1 < argc)
            raw = argv[++i];
        else if (!strcmp(a, "--wo") && i + 2 < argc) {
            if (!tool_number(prog, "--wo THETA", argv[++i], 0, 180, 0, &theta) ||
                !tool_number(prog, "--wo PHI", argv[++i], -360, 360, 0, &phi))
                return 2;
        } else if (!strcmp(a, "-o") && i + 1 < argc)
            out = argv[++i];
        else if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            help();
            return 0;
        } else if (!strcmp(a, "--version")) {
            printf("materia-lobe (materia) %s, %s\n", mt_version(), mt_precision());
            return 0;
        } else if (a[0] == '-' && a[1] == '-') {
            fprintf(stderr, "%s: unknown option \"%s\"\n", prog, a);
            usage(stderr);
            return 2;
        } else
            first = i--;
    }
    if (!first || !out || theta < 0) {
        fprintf(stderr, "%s: %s\n", prog, !out ? "-o FILE.png is needed" : theta < 0 ? "--wo THETA PHI is needed" : "no statements");
        usage(stderr);
        return 2;
    }
    {
        /* a typo in an output path fails now, not after the measurement */
        char raw_path[1100];
        snprintf(raw_path, sizeof raw_path, "%s-A-fcos.pfm", raw ? raw : "");
        if (mt_image_check_writable(out, &err) != MT_OK || (raw && mt_image_check_writable(raw_path, &err) != MT_OK)) {
            fprintf(stderr, "%s: %s\n", prog, err.message);
            return 1;
        }
    }
    for (i = first; i < argc; ++i) len += strlen(argv[i]) + 1;
    statements = malloc(len);
    if (!statements) return 1;
    statements[0] = 0;
    for (i = first; i < argc; ++i) {
        if (i > first) strcat(statements, " ");
        strcat(statements, argv[i]);
        if (strchr(argv[i], '\n')) {
            fprintf(stderr, "%s: a statement argument holds a newline: give the statements on one line\n", prog);
            return 2;
        }
    }
    wo[0] = sin(theta * PI / 180) * cos(phi * PI / 180);
    wo[1] = sin(theta * PI / 180) * sin(phi * PI / 180);
    wo[2] = cos(theta * PI / 180);

    nimpl = against ? 2 : 1;
    for (i = 0; i < nimpl; ++i) {
        const char *cmd = i == 0 ? impl_cmd : against;
        char e[256];
        memset(&m[i], 0, sizeof m[i]);
        m[i].label = cmd ? cmd : "materia (in-process)";
        if (!cmd) {
            if (!(m[i].q = mt_query_create(NULL, &err))) die("%s%s", err.message, "");
        } else if (!pc_start(&m[i].child, cmd, (int)(timeout * 1000), e, sizeof e))
            die("%s: %s", cmd, e);
        measure(&m[i], mode, statements, wo, phi * PI / 180, samples, &L[i]);
    }
    rows = nimpl == 2 ? 3 : 1;
    if (rows == 3) {
        int x, y;
        for (y = 0; y < LL_H; ++y)
            for (x = 0; x < LL_W; ++x) {
                L[2].fcos[y][x] = L[0].fcos[y][x] - L[1].fcos[y][x];
                L[2].pdf[y][x] = L[0].pdf[y][x] - L[1].pdf[y][x];
                L[2].hist[y][x] = L[0].hist[y][x] - L[1].hist[y][x];
            }
        for (i = 0; i < POLAR_N; ++i) {
            L[2].polar_f[i] = L[0].polar_f[i] - L[1].polar_f[i];
            L[2].polar_pdf[i] = L[0].polar_pdf[i] - L[1].polar_pdf[i];
        }
    }

    width = LOBE_WIDTH;
    per_line = (width - 2 * GAP) / MT__FONT_ADVANCE;
    lines_stmt = (int)((strlen(statements) + (size_t)per_line - 1) / (size_t)per_line);
    if (lines_stmt < 1) lines_stmt = 1;
    height = LOBE_HEIGHT(nimpl, lines_stmt, rows);
    if (mt_image_create(&img, width, height, 3, &err)) die("%s%s", err.message, "");
    for (i = 0; i < width * height * 3; ++i) img.data[i] = 0.02f;
    snprintf(header[0], sizeof header[0], "materia-lobe  mode %s  wo theta %g phi %g deg  %ld samples", mode, theta, phi,
             samples);
    snprintf(header[1], sizeof header[1], "lat-long: phi 0..360 left to right, theta 0 (+z, top) .. 180; f = mean of r,g,b");
    mt__draw_text(&img, GAP, GAP, header[0], 1, white);
    mt__draw_text(&img, GAP, GAP + LINE, header[1], 1, white);
    for (i = 0; i < nimpl; ++i) {
        snprintf(header[2 + i], sizeof header[2 + i], "%c: %.150s  (%.2f%% of samples failed)", 'A' + i, m[i].label,
                 samples ? 100.0 * L[i].failed / samples : 0.0);
        mt__draw_text(&img, GAP, GAP + LINE * (2 + i), header[2 + i], 1, i ? cyan : yellow);
    }
    for (i = 0; i < lines_stmt; ++i) {
        char piece[256];
        snprintf(piece, sizeof piece, "%.*s", per_line, statements + (size_t)i * (size_t)per_line);
        mt__draw_text(&img, GAP, GAP + LINE * (2 + nimpl + i), piece, 1, white);
    }
    for (r = 0; r < rows; ++r) {
        int y0 = LOBE_MAP_Y(nimpl, lines_stmt, r), diff = r == 2;
        const char *tag = r == 0 ? "A" : r == 1 ? "B" : "A-B";
        char t[64];
        double hp = fmax(map_max(L[r].pdf, diff), 0);
        if (!(hp > 0)) hp = map_max(L[r].hist, diff);
        snprintf(t, sizeof t, "%s f cos", tag);
        draw_map(&img, LOBE_MAP_X(0), y0, L[r].fcos, map_max(L[r].fcos, diff), diff, t);
        snprintf(t, sizeof t, "%s pdf", tag);
        draw_map(&img, LOBE_MAP_X(1), y0, L[r].pdf, hp, diff, t);
        snprintf(t, sizeof t, "%s samples (density, pdf's scale)", tag);
        draw_map(&img, LOBE_MAP_X(2), y0, L[r].hist, diff ? map_max(L[r].hist, 1) : hp, diff, t);
        draw_polar(&img, LOBE_MAP_X(3), y0, L[r].polar_f, L[r].polar_pdf, theta * PI / 180, diff);
        if (raw) {
            const char *names[3] = {"A", "B", "diff"};
            if (!write_raw(raw, names[r], "fcos", L[r].fcos) || !write_raw(raw, names[r], "pdf", L[r].pdf) ||
                !write_raw(raw, names[r], "hist", L[r].hist))
                return 1;
        }
    }
    if (mt_image_write(out, &img, NULL, 0, &err)) {
        fprintf(stderr, "%s: %s\n", prog, err.message);
        return 1;
    }
    for (i = 0; i < nimpl; ++i) {
        if (m[i].q) mt_query_destroy(m[i].q);
        else pc_stop(&m[i].child);
    }
    mt_image_destroy(&img);
    free(statements);
    printf("%s: %dx%d\n", out, width, height);
    return 0;
}
