/*
 * materia/tools/sheet.h -- contact sheets: images laid out in a grid with a label
 * under each, tone mapped for display (make demo shows every material so).
 *
 * Thread safety: may be called from any thread at once.
 */
#ifndef MATERIA_TOOLS_SHEET_H
#define MATERIA_TOOLS_SHEET_H

#include "materia/error.h"
#include "materia/image.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct mt_sheet_entry {
    const char *label;        /* drawn under the image (NULL: none) */
    const mt_image *image;
} mt_sheet_entry;

typedef struct mt_sheet_options {
    int columns;     /* images per row; 0: the smallest c with c * c >= n */
    int font_scale;  /* image pixels per font pixel (default 1: 5x7 glyphs) */
    double exposure; /* stops: pixel values are multiplied by 2^exposure */
    int gap;         /* pixels around and between the cells (default 4) */
} mt_sheet_options;

/* columns 0, font_scale 1, exposure 0, gap 4. */
MT_API mt_sheet_options mt_sheet_defaults(void);

/* Lays out n images in rows of opt->columns cells, each as wide and high as
 * the largest image (smaller ones centred at the top of theirs) over a dark
 * grey background, with the label centred under its image in the built-in
 * 5x7 font, in white (cut to the cell's width). Tone mapping: times
 * 2^exposure, clamped to [0, 1]; a one-channel image is shown grey, alpha is
 * ignored, and a NaN or infinite pixel is drawn magenta (it is a bug in
 * whatever made the image). *out is a new RGB image of linear values in
 * [0, 1]: mt_image_write to a .png applies sRGB. opt NULL: the defaults. */
MT_API mt_status mt_sheet_make(const mt_sheet_entry *entries, int n, const mt_sheet_options *opt,
                               mt_image *out, mt_error *err);

#ifdef __cplusplus
}
#endif

#endif
