/*
 * materia-merl: the MERL table of any materia material.
 *
 *   materia-merl --out plastic.binary \
 *       'Material "plastic" "rgb Kd" [0.3 0.1 0.1] "float roughness" [0.05]'
 *
 * The statements (pbrt-v2's scene language: transforms, Texture, Material,
 * MakeNamedMaterial, NamedMaterial, AttributeBegin/End) set up a graphics
 * state; the material they leave current is evaluated at the standard
 * shading point (n = +z, dpdu = +x, geometric normal = shading normal) on
 * the grid of pbrt-v2's RegularHalfangleBRDF (90 theta_h bins on a square-
 * root scale, 90 theta_d, 180 phi_d; the value at each bin's lower corner,
 * MERL's grid point, or with --at centre at its centre) and written in
 * MERL's binary format with pbrt-v2's channel scales, so that pbrt-v2 (or
 * materia) reading the file gets the material's f back at those points. The file is written to a temporary file next to --out
 * and renamed into place.
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "materia.h"
#include "materia/tools/merl.h"
#include "toolargs.h"
#include "materia/measured.h"

static void usage(FILE *f)
{
    fprintf(f,
            "usage: materia-merl --out FILE [--mode pbrt-v2|corrected] [--at corner|centre]\n"
            "                    [--dir DIR] STATEMENT...\n"
            "       materia-merl --help | --version\n"
            "Writes the MERL table (MERL's binary format, pbrt-v2's 90 x 90 x 180 half-angle grid)\n"
            "of the material that the pbrt-v2 statements leave current, evaluated at the standard\n"
            "shading point (n = +z, dpdu = +x). The statement arguments are joined by newlines;\n"
            "a single \"-\" reads them from standard input.\n"
            "  --out FILE   the file to write (required; through a temporary file next to it)\n"
            "  --mode M     pbrt-v2 (the default) or corrected\n"
            "  --at P       where each entry is sampled in its bin: corner (MERL's grid points,\n"
            "               the default) or centre (half the lookup error; a table of a MERL\n"
            "               material reproduces its table)\n"
            "  --dir DIR    the directory relative file names resolve against (default: .)\n"
            "  --help, -h   this text;  --version  materia's version and precision\n"
            "Exit status: 0 written, 1 error (message on standard error), 2 bad usage.\n");
}

static void warn(void *ctx, const char *file, int line, const char *message)
{
    (void)ctx;
    if (file && file[0] && line > 0)
        fprintf(stderr, "materia-merl: warning: %s:%d: %s\n", file, line, message);
    else
        fprintf(stderr, "materia-merl: warning: %s\n", message);
}

/* Appends s and a newline to *text (growing it); 0 when out of memory. */
static int append(char **text, size_t *len, const char *s, size_t n)
{
    char *t = realloc(*text, *len + n + 2);
    if (!t) return 0;
    memcpy(t + *len, s, n);
    *len += n;
    t[(*len)++] = '\n';
    t[*len] = '\0';
    *text = t;
    return 1;
}

static int read_stdin(char **text, size_t *len)
{
    char buf[4096];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, stdin)) > 0)
        if (!append(text, len, buf, n)) return 0;
    return !ferror(stdin);
}

int main(int argc, char **argv)
{
    const char *out = NULL;
    mt_merl_options opt = {MT_MODE_PBRT_V2, MT_MERL_AT_CORNER, NULL, warn, NULL};
    char *text = NULL, msg[1024];
    size_t len = 0;
    int i, ok = 1;
    mt_error err;
    for (i = 1; i < argc && ok; ++i) {
        if (!strcmp(argv[i], "--version")) {
            /* (mt_image_formats also links every format: an imagemap
             * texture of the statements reads them) */
            printf("materia-merl (materia) %s, %s, image formats %s\n", mt_version(), mt_precision(),
                   mt_image_formats());
            free(text);
            return 0;
        } else if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
            usage(stdout);
            free(text);
            return 0;
        } else if (i + 1 == argc && (!strcmp(argv[i], "--out") || !strcmp(argv[i], "--dir") ||
                                     !strcmp(argv[i], "--mode") || !strcmp(argv[i], "--at"))) {
            free(text);
            return tool_no_value("materia-merl", argv[i]);
        } else if (!strcmp(argv[i], "--out") && i + 1 < argc) {
            out = argv[++i];
        } else if (!strcmp(argv[i], "--dir") && i + 1 < argc) {
            opt.dir = argv[++i];
            if (!tool_directory("materia-merl", "--dir", opt.dir)) {
                free(text);
                return 1;
            }
        } else if (!strcmp(argv[i], "--mode") && i + 1 < argc) {
            if (mt_mode_parse(argv[++i], &opt.mode, NULL) != MT_OK) {
                fprintf(stderr, "materia-merl: unknown mode \"%s\" (pbrt-v2 or corrected)\n", argv[i]);
                free(text);
                return 2;
            }
        } else if (!strcmp(argv[i], "--at") && i + 1 < argc) {
            ++i;
            if (strcmp(argv[i], "corner") && strcmp(argv[i], "centre") && strcmp(argv[i], "center")) {
                fprintf(stderr, "materia-merl: --at takes corner or centre, not \"%s\"\n", argv[i]);
                free(text);
                return 2;
            }
            opt.at = argv[i][0] == 'c' && argv[i][1] == 'e' ? MT_MERL_AT_CENTRE : MT_MERL_AT_CORNER;
        } else if (!strcmp(argv[i], "-") && !text) {
            ok = read_stdin(&text, &len);
        } else if (argv[i][0] == '-' && argv[i][1] == '-') {
            fprintf(stderr, "materia-merl: unknown option %s\n", argv[i]);
            usage(stderr);
            free(text);
            return 2;
        } else {
            ok = append(&text, &len, argv[i], strlen(argv[i]));
        }
    }
    if (!ok) {
        fprintf(stderr, "materia-merl: cannot read the statements\n");
        free(text);
        return 1;
    }
    if (!out || !text) {
        fprintf(stderr, "materia-merl: %s\n", !out ? "--out FILE is required" : "no statements given");
        usage(stderr);
        free(text);
        return 2;
    }
    if (mt_merl_write_statements(text, &opt, out, &err) != MT_OK) {
        fprintf(stderr, "materia-merl: %s\n", mt_error_format(&err, msg, sizeof msg));
        free(text);
        return 1;
    }
    printf("wrote %s: %d x %d x %d MERL table (%s mode, sampled at the bin %s)\n", out,
           MT_MERL_THETA_H, MT_MERL_THETA_D, MT_MERL_PHI_D, mt_mode_name(opt.mode),
           opt.at == MT_MERL_AT_CENTRE ? "centres" : "corners");
    free(text);
    return 0;
}
