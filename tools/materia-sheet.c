/*
 * materia-sheet: a contact sheet of images with labels (include/materia/tools/sheet.h).
 *
 *   materia-sheet -o SHEET.png [--columns N] [--exposure STOPS] [--font-scale K]
 *                 LABEL=IMAGE ... | IMAGE ...
 *
 * An argument without '=' is labelled with its file name without folder and
 * extension. Values are multiplied by 2^STOPS, clamped to [0, 1] and written
 * as sRGB (a .png; an .exr or .pfm keeps the linear values). Exit status 0
 * when the sheet was written, 1 on an error (naming the file).
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "materia.h"
#include "materia/image.h"
#include "materia/tools/sheet.h"
#include "toolargs.h"

static const char *prog = "materia-sheet";

static int usage(FILE *f)
{
    fprintf(f,
            "usage: %s -o SHEET.png [--columns N] [--exposure STOPS] [--font-scale K]\n"
            "       LABEL=IMAGE ... (or IMAGE: labelled with its file name)\n"
            "       %s --help | --version\n",
            prog, prog);
    if (f == stdout) /* --help: every option with its default */
        fputs("A labelled contact sheet of images (EXR, PNG or PFM), as make demo makes one.\n"
              "  -o SHEET.png       the sheet (required; .png, .exr or .pfm)\n"
              "  --columns N        images per row, 0 to 4096 (default 0: the smallest N with N x N\n"
              "                     at least the number of images)\n"
              "  --exposure STOPS   pixel values times 2^STOPS, -64 to 64 (default 0)\n"
              "  --font-scale K     image pixels per font pixel of the labels, 1 to 16 (default 1)\n"
              "  --help, -h         this text;  --version  materia's version and precision\n"
              "Exit status: 0 written, 1 failure (an image unreadable, the sheet not written),\n"
              "2 wrong command line.\n",
              f);
    return f == stdout ? 0 : 2;
}

/* An integer option's value in [lo, hi]. */
static int integer(const char *opt, const char *s, long lo, long hi, int *out)
{
    double v;
    if (!tool_number(prog, opt, s, (double)lo, (double)hi, 1, &v)) return 0;
    *out = (int)v;
    return 1;
}

/* The path of "label=path" or of a bare path. */
static const char *split_path(const char *arg)
{
    const char *eq = strchr(arg, '=');
    return eq ? eq + 1 : arg;
}

/* Splits "label=path" (or a bare path) into the entry's label (a new
 * string) and returns the path. */
static const char *split(const char *arg, char **label)
{
    const char *eq = strchr(arg, '='), *path = split_path(arg), *base, *dot;
    size_t n;
    if (eq) {
        base = arg;
        n = (size_t)(eq - arg);
    } else {
        base = strrchr(arg, '/') ? strrchr(arg, '/') + 1 : arg;
        dot = strrchr(base, '.');
        n = dot && dot > base ? (size_t)(dot - base) : strlen(base);
    }
    if ((*label = malloc(n + 1)) != NULL) {
        memcpy(*label, base, n);
        (*label)[n] = 0;
    }
    return path;
}

int main(int argc, char **argv)
{
    mt_sheet_options opt = mt_sheet_defaults();
    mt_sheet_entry *entries;
    mt_image *images, sheet = {0, 0, 0, NULL};
    char **labels;
    const char *out = NULL;
    mt_error err;
    int i, n = 0, status = 0;
    for (i = 1; i < argc; ++i)
        if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) return usage(stdout);
        else if (!strcmp(argv[i], "--version")) {
            printf("%s (materia) %s, %s\n", prog, mt_version(), mt_precision());
            return 0;
        }
    entries = calloc((size_t)argc, sizeof *entries);
    images = calloc((size_t)argc, sizeof *images);
    labels = calloc((size_t)argc, sizeof *labels);
    if (!entries || !images || !labels) {
        fprintf(stderr, "%s: out of memory\n", prog);
        return 1;
    }
    mt_error_clear(&err);
    /* the options first, and the output path checked, before any image is read */
    for (i = 1; i < argc && status == 0; ++i) {
        const char *o = argv[i], *val = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(o, "-o") || !strcmp(o, "--columns") || !strcmp(o, "--font-scale") || !strcmp(o, "--exposure")) {
            if (!val)
                status = tool_no_value(prog, o);
            else if (!strcmp(o, "-o"))
                out = argv[++i];
            else if (!strcmp(o, "--columns"))
                status = integer(o, argv[++i], 0, 4096, &opt.columns) ? 0 : 2;
            else if (!strcmp(o, "--font-scale"))
                status = integer(o, argv[++i], 1, 16, &opt.font_scale) ? 0 : 2;
            else
                status = tool_number(prog, o, argv[++i], -64, 64, 0, &opt.exposure) ? 0 : 2;
        } else if (o[0] == '-') {
            fprintf(stderr, "%s: unknown option %s\n", prog, o);
            status = usage(stderr);
        } else if (!*split_path(o)) {
            fprintf(stderr, "%s: \"%s\" names no image (LABEL=IMAGE)\n", prog, o);
            status = 2;
        } else
            n++;
    }
    if (status == 0 && (!out || n == 0)) {
        fprintf(stderr, "%s: %s\n", prog, !out ? "no output file (-o SHEET.png)" : "no images");
        status = usage(stderr);
    }
    if (status == 0 && mt_image_check_writable(out, &err) != MT_OK) {
        fprintf(stderr, "%s: %s\n", prog, err.message);
        status = 1;
    }
    for (i = 1, n = 0; i < argc && status == 0; ++i) {
        const char *o = argv[i];
        if (o[0] == '-')
            ++i; /* an option and its value, read above */
        else {
            const char *path = split(o, &labels[n]);
            if (!labels[n] || mt_image_read(path, &images[n], &err) != MT_OK) {
                fprintf(stderr, "%s: %s\n", prog, labels[n] ? err.message : "out of memory");
                status = 1;
            } else {
                entries[n].label = labels[n];
                entries[n].image = &images[n];
                n++;
            }
        }
    }
    if (status == 0) {
        if (mt_sheet_make(entries, n, &opt, &sheet, &err) != MT_OK ||
            mt_image_write(out, &sheet, NULL, 0, &err) != MT_OK) {
            fprintf(stderr, "%s: %s\n", prog, err.message);
            status = 1;
        }
        mt_image_destroy(&sheet);
    }
    for (i = 0; i <= n && i < argc; ++i) {
        mt_image_destroy(&images[i]);
        free(labels[i]);
    }
    free(entries);
    free(images);
    free(labels);
    return status;
}
