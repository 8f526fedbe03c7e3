/*
 * The pictures and tools around image comparison: the 5x7 font, the
 * false-colour heat map, the contact sheet (pixel by pixel, then written as
 * PNG and read back), and the two programs, materia-imgdiff and
 * materia-sheet, run with system(): their output, exit statuses and error
 * messages (missing file, size mismatch, bad arguments).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>
#include "image/font.h"
#include "materia/tools/imgcmp.h"
#include "materia/tools/sheet.h"
#include "support/check.h"
#include "support/timage.h"
#include "support/tfiles.h"
#include "support/ttools.h"

static const char *dir;   /* the test's private directory */
static const char *bindir; /* where the tools are */

/* The largest |difference| between a pixel's first three channels and rgb. */
static double off(const mt_image *img, int x, int y, const float *rgb)
{
    const float *p = t_image_px(img, x, y);
    return fmax(fabs(p[0] - rgb[0]), fmax(fabs(p[1] - rgb[1]), fabs(p[2] - rgb[2])));
}

/* Reads dir/name (a PNG) and checks its size and, when want is not NULL,
 * that pixel (x, y) is within 8-bit sRGB rounding of want. */
static void check_png(const char *name, int w, int h, int x, int y, const float *want,
                      const char *check)
{
    mt_image back;
    mt_error err;
    if (mt_image_read(t_tmp_path(name), &back, &err) != MT_OK) {
        t_fail(check, "%s", err.message);
        return;
    }
    t_check(back.width == w && back.height == h && (!want || off(&back, x, y, want) < 0.005),
            check, "%d x %d (want %d x %d), pixel (%d, %d) off by %g", back.width, back.height, w,
            h, x, y, want ? off(&back, x, y, want) : 0.0);
    mt_image_destroy(&back);
}

/* Writes img to dir/name, then check_png. */
static void check_written(const char *name, const mt_image *img, int x, int y, const float *want,
                          const char *check)
{
    mt_error err;
    if (mt_image_write(t_tmp_path(name), img, NULL, 0, &err) != MT_OK)
        t_fail(check, "%s", err.message);
    else
        check_png(name, img->width, img->height, x, y, want, check);
}

/* ---- font --------------------------------------------------------------- */

static void test_font(void)
{
    static const unsigned char A[7] = {0x0E, 0x11, 0x11, 0x11, 0x1F, 0x11, 0x11};
    static const char set[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789";
    static const float white[3] = {1, 1, 1};
    mt_image img = t_image_make(16, 20, 3, 0);
    int i, j, same = 0, empty = 0, wrong = 0, r, c;
    t_check(memcmp(mt__font_glyph('A'), A, 7) == 0, "font: A", "glyph differs");
    t_check(mt__font_glyph(200) == mt__font_glyph('?') && mt__font_glyph('\n') == mt__font_glyph('?'),
            "font: characters outside ASCII show '?'", "no");
    for (i = 0; set[i]; ++i) {
        const unsigned char *g = mt__font_glyph(set[i]);
        empty += !(g[0] | g[1] | g[2] | g[3] | g[4] | g[5] | g[6]);
        for (j = 0; j < i; ++j) same += memcmp(g, mt__font_glyph(set[j]), 7) == 0;
        for (r = 0; r < 7; ++r) wrong += g[r] > 0x1F;
    }
    t_check(same == 0 && empty == 0 && wrong == 0,
            "font: letters and digits are 62 distinct, non-empty 5-pixel-wide glyphs",
            "%d alike, %d empty, %d rows too wide", same, empty, wrong);
    t_check(mt__text_width("abc", 2) == 34 && mt__text_width("", 1) == 0,
            "font: text width is 6 per character less the last space", "%d",
            mt__text_width("abc", 2));
    /* "A" at scale 2 from (3, 2): font pixel (col, row) covers image pixels
     * (3 + 2 col .. +1, 2 + 2 row .. +1) */
    mt__draw_text(&img, 3, 2, "A", 2, white);
    for (r = 0, wrong = 0; r < 7; ++r)
        for (c = 0; c < 5; ++c) {
            int on = A[r] >> (4 - c) & 1;
            wrong += t_image_px(&img, 3 + 2 * c, 2 + 2 * r)[0] != on || t_image_px(&img, 4 + 2 * c, 3 + 2 * r)[1] != on;
        }
    t_check(wrong == 0 && t_image_px(&img, 2, 2)[0] == 0 && t_image_px(&img, 13, 2)[0] == 0,
            "font: A drawn at scale 2 covers exactly its pixels", "%d wrong", wrong);
    /* clipped at every edge, nothing written outside (the sanitizer build
     * checks the memory) */
    mt__draw_text(&img, -7, -3, "WW", 3, white);
    mt__draw_text(&img, 12, 17, "WW", 3, white);
    t_pass("font: text is clipped at the image's edges");
    mt_image_destroy(&img);
}

/* ---- heat map ----------------------------------------------------------- */

/* The colour scale's stops, as linear values (written as sRGB bytes). */
static void stop(int i, float *rgb)
{
    static const float s[5][3] = {{0, 0, 4}, {87, 16, 110}, {188, 55, 84}, {249, 142, 9}, {252, 255, 164}};
    int c;
    for (c = 0; c < 3; ++c) rgb[c] = mt_srgb_to_linear(s[i][c] / 255);
}

static void test_heatmap(void)
{
    /* a 9 x 6 image in blocks of 4: 3 x 2 blocks holding 0, 0.05, 0.1, 0.2
     * (above vmax = 0.1), and -0.05 in channel 2 with 0.025 in channel 0 */
    mt_image blocks = t_image_make(3, 2, 3, 0), out;
    mt_error err;
    float want[3];
    double worst = 0;
    int x, y;
    t_image_px(&blocks, 1, 0)[1] = 0.05f;
    t_image_px(&blocks, 2, 0)[0] = 0.1f;
    t_image_px(&blocks, 0, 1)[2] = 0.2f;
    t_image_px(&blocks, 1, 1)[0] = 0.025f;
    t_image_px(&blocks, 1, 1)[2] = -0.05f;
    if (mt_imgcmp_heatmap(&blocks, 4, 9, 6, 0.1, 1, &out, &err) != MT_OK) {
        t_fail("heat map", "%s", err.message);
        mt_image_destroy(&blocks);
        return;
    }
    t_check(out.width == 9 && out.height == 6 + 19 && out.channels == 3,
            "heat map: the picture and a 19-pixel colour bar", "%d x %d", out.width, out.height);
    stop(0, want);
    for (y = 0; y < 4; ++y)
        for (x = 0; x < 4; ++x) worst = fmax(worst, off(&out, x, y, want));
    stop(2, want);
    for (y = 0; y < 4; ++y)
        for (x = 4; x < 8; ++x) worst = fmax(worst, off(&out, x, y, want));
    stop(4, want);
    worst = fmax(worst, off(&out, 8, 0, want));
    worst = fmax(worst, off(&out, 0, 4, want)); /* 0.2 saturates */
    stop(2, want);
    worst = fmax(worst, off(&out, 5, 5, want)); /* max |v| over channels */
    t_check(worst < 1e-6, "heat map: blocks take the scale's colours (0, vmax / 2, vmax, above)",
            "off by %g", worst);
    stop(0, want);
    worst = off(&out, 0, 6 + 4, want);
    stop(4, want);
    worst = fmax(worst, off(&out, 8, 6 + 4, want));
    t_check(worst < 1e-6, "heat map: the colour bar runs from 0 to vmax", "off by %g", worst);
    stop(2, want);
    check_written("heat.png", &out, 4, 0, want, "heat map: written as PNG and read back");
    mt_image_destroy(&out);
    t_check(mt_imgcmp_heatmap(&blocks, 4, 13, 6, 0.1, 0, &out, &err) == MT_ERR_INVALID &&
                strstr(err.message, "does not cover"),
            "heat map: a block map of the wrong size is refused", "%s", err.message);
    t_check(mt_imgcmp_heatmap(&blocks, 4, 9, 6, 0, 0, &out, &err) == MT_ERR_INVALID,
            "heat map: vmax 0 is refused", "%s", err.message);
    mt_image_destroy(&blocks);
}

/* ---- contact sheet ------------------------------------------------------- */

/* Three images, two columns, gap 4: cells of 10 x 8 (the largest image) plus
 * a label row of 4 + 7; the sheet is 2 * 10 + 3 * 4 = 32 wide and
 * 2 * (8 + 11) + 3 * 4 = 50 high. */
static void test_sheet(void)
{
    mt_image red = t_image_make(10, 8, 3, 0), grey = t_image_make(6, 4, 1, 2), odd = t_image_make(10, 8, 4, 0.25f);
    mt_image out;
    mt_sheet_entry e[3];
    mt_sheet_options o = mt_sheet_defaults();
    mt_error err;
    static const float bg[3] = {0.01f, 0.01f, 0.01f}, white[3] = {1, 1, 1},
                       magenta[3] = {1, 0, 1};
    float want[3] = {0.5f, 0, 0};
    double worst;
    int x, y;
    for (y = 0; y < 8; ++y)
        for (x = 0; x < 10; ++x) t_image_px(&red, x, y)[0] = 0.5f;
    t_image_px(&odd, 3, 2)[1] = NAN;
    e[0].label = "A", e[0].image = &red;
    e[1].label = "grey", e[1].image = &grey;
    e[2].label = "a label far too long for its cell", e[2].image = &odd;
    o.columns = 2;
    if (mt_sheet_make(e, 3, &o, &out, &err) != MT_OK) {
        t_fail("contact sheet", "%s", err.message);
        return;
    }
    t_check(out.width == 32 && out.height == 50, "contact sheet: size of a 2 x 2 grid", "%d x %d",
            out.width, out.height);
    worst = fmax(off(&out, 4, 4, want), off(&out, 13, 11, want)); /* first image's corners */
    worst = fmax(worst, off(&out, 0, 0, bg));
    worst = fmax(worst, off(&out, 19, 4, bg)); /* left of the centred 6-wide image */
    worst = fmax(worst, off(&out, 20, 4, white)); /* grey 2 clamped to 1 */
    worst = fmax(worst, off(&out, 25, 7, white));
    worst = fmax(worst, off(&out, 20, 8, bg)); /* below it: cell background */
    worst = fmax(worst, off(&out, 4 + 3, 4 + 19 + 4 + 2, magenta)); /* the NaN */
    t_check(worst < 1e-6, "contact sheet: images placed, centred, clamped; NaN magenta", "off by %g",
            worst);
    /* "A" centred under a 10-pixel cell: x = 4 + (10 - 5) / 2 = 6, y = 4 + 8 + 4
     * = 16; its top row .###. lights x = 7, 8, 9 */
    worst = fmax(off(&out, 7, 16, white), off(&out, 9, 16, white));
    worst = fmax(worst, fmax(off(&out, 6, 16, bg), off(&out, 10, 16, bg)));
    worst = fmax(worst, off(&out, 6, 20, white)); /* the crossbar row */
    t_check(worst < 1e-6, "contact sheet: the label is centred under its image", "off by %g", worst);
    {
        /* the third label, at y = 27 + 8 + 4: only "a" fits in 10 pixels */
        int lit = 0, spill = 0;
        for (y = 39; y < 46; ++y)
            for (x = 0; x < 32; ++x)
                if (t_image_px(&out, x, y)[1] == 1) {
                    if (x >= 4 && x < 14)
                        lit++;
                    else
                        spill++;
                }
        t_check(lit > 0 && spill == 0, "contact sheet: a long label is cut to its cell",
                "%d pixels lit in the cell, %d outside", lit, spill);
    }
    check_written("sheet.png", &out, 4, 4, want, "contact sheet: written as PNG and read back");
    mt_image_destroy(&out);
    o.exposure = -1;
    want[0] = 0.25f;
    if (mt_sheet_make(e, 1, &o, &out, &err) == MT_OK) {
        t_check(out.width == 18 && off(&out, 4, 4, want) < 1e-7,
                "contact sheet: exposure -1 halves; one image, one column", "%d wide", out.width);
        mt_image_destroy(&out);
    } else
        t_fail("contact sheet: exposure", "%s", err.message);
    e[1].image = NULL;
    t_check(mt_sheet_make(e, 3, NULL, &out, &err) == MT_ERR_INVALID && strstr(err.message, "grey"),
            "contact sheet: an entry without image is named", "%s", err.message);
    t_check(mt_sheet_make(e, 0, NULL, &out, &err) == MT_ERR_INVALID,
            "contact sheet: no images is an error", "%s", err.message);
    mt_image_destroy(&red);
    mt_image_destroy(&grey);
    mt_image_destroy(&odd);
}

/* ---- the tools ----------------------------------------------------------- */

/* Writes img into the test's directory as name. */
static int write_image(const char *name, const mt_image *img)
{
    mt_error err;
    if (mt_image_write(t_tmp_path(name), img, NULL, 0, &err) == MT_OK) return 1;
    t_fail("tools: test images", "%s", err.message);
    return 0;
}

static void test_tools(void)
{
    mt_image a = t_image_make(16, 12, 3, 0.5f), b = t_image_make(16, 12, 3, 0.5f);
    mt_image c = t_image_make(8, 8, 3, 0.5f), v = t_image_make(16, 12, 3, 1e-6f);
    int x, y, ok;
    char path[1100];
    snprintf(path, sizeof path, "%s/materia-imgdiff", bindir);
    for (y = 0; y < 4; ++y)
        for (x = 0; x < 4; ++x) t_image_px(&a, x, y)[0] = 0.55f; /* +10% in one block */
    ok = access(path, X_OK) == 0 && write_image("a.pfm", &a) && write_image("b.pfm", &b) &&
         write_image("c.pfm", &c) && write_image("v.exr", &v);
    mt_image_destroy(&a);
    mt_image_destroy(&b);
    mt_image_destroy(&c);
    mt_image_destroy(&v);
    if (!ok) {
        t_fail("tools", "%s is not built or the test images cannot be written", path);
        return;
    }
    t_tool_check("imgdiff: compares and prints pbrt-v2's metric (one block 10% off)", "materia-imgdiff",
         "a.pfm b.pfm", 0, "out.txt", "noise-max 0.0980392");
    t_check(t_file_holds("out.txt", "noise-mean ") && t_file_holds("out.txt", "rmse ") &&
                t_file_holds("out.txt", "relmse ") && t_file_holds("out.txt", "max-diff 0.05") &&
                t_file_holds("out.txt", "lum-ratio ") && !t_file_holds("out.txt", "ztest"),
            "imgdiff: prints noise, rmse, relmse, max-diff, lum-ratio (no z-test without variance)",
            "output incomplete");
    t_tool_check("imgdiff: a missing file is exit 1 naming it", "materia-imgdiff", "a.pfm missing.exr", 1,
         "err.txt", "missing.exr: cannot open");
    t_tool_check("imgdiff: a size mismatch is exit 1", "materia-imgdiff", "a.pfm c.pfm", 1, "err.txt",
         "size mismatch: c.pfm is 8 x 8 but a.pfm is 16 x 12");
    t_tool_check("imgdiff: --fail-above below the difference is exit 1", "materia-imgdiff",
         "a.pfm b.pfm --fail-above 0.001", 1, "err.txt", "exceeds 0.001");
    t_tool_check("imgdiff: --fail-above over the difference is exit 0", "materia-imgdiff",
         "a.pfm b.pfm --fail-above 0.01", 0, "out.txt", "noise-mean");
    t_tool_check("imgdiff: the z-test finds the 10% block and --fail-ztest exits 1", "materia-imgdiff",
         "a.pfm b.pfm --var-a v.exr --var-b v.exr --fail-ztest", 1, "out.txt", "ztest FAIL");
    t_tool_check("imgdiff: an image against itself passes the z-test", "materia-imgdiff",
         "b.pfm b.pfm --var-b v.exr --heatmap z.png --heatmap-z", 0, "out.txt", "ztest pass");
    t_tool_check("imgdiff: writes the heat map", "materia-imgdiff", "a.pfm b.pfm --heatmap heat.png", 0,
         "out.txt", "heatmap heat.png");
    check_png("heat.png", 16, 12 + 19, 0, 0, NULL, "imgdiff: the heat map is readable");
    t_tool_check("imgdiff: one image is exit 2 (usage)", "materia-imgdiff", "a.pfm", 2, "err.txt", "usage");
    t_tool_check("imgdiff: a bad number is exit 2 (usage)", "materia-imgdiff", "--block x a.pfm b.pfm", 2,
         "err.txt", "--block needs a whole number between 1 and 4096");

    t_tool_check("sheet: writes a contact sheet", "materia-sheet", "-o s.png --columns 2 one=a.pfm b.pfm",
         0, "err.txt", "");
    check_png("s.png", 2 * 16 + 3 * 4, 12 + 11 + 2 * 4, 0, 0, NULL,
              "sheet: the contact sheet is readable");
    t_tool_check("sheet: a missing image is exit 1 naming it", "materia-sheet", "-o s2.png x=missing.pfm",
         1, "err.txt", "missing.pfm: cannot open");
    t_tool_check("sheet: no -o is exit 2 (usage)", "materia-sheet", "a.pfm", 2, "err.txt", "no output file");
    t_tool_check("sheet: --help is exit 0", "materia-sheet", "--help", 0, "out.txt", "usage");
    t_tool_check("imgdiff: --help is exit 0", "materia-imgdiff", "--help", 0, "out.txt", "usage");
}

int main(int argc, char **argv)
{
    (void)argc;
    bindir = t_tool_bindir(argv[0]);
    if (!(dir = t_tmpdir_create("imgtools"))) {
        t_fail("imgtools", "cannot create a temporary directory");
        return t_status();
    }
    test_font();
    /* the heat map and the sheet are checked as PNG files, the tools with a
     * variance image in EXR */
    if (t_has_format("png", "heat map and contact sheet (written as PNG)")) {
        test_heatmap();
        test_sheet();
    }
    if (t_has_format("png", "imgdiff and sheet (PNG outputs)") && t_has_format("exr", "imgdiff (an EXR variance)"))
        test_tools();
    t_tmpdir_remove();
    return t_status();
}
