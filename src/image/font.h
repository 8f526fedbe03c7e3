/*
 * Internal: a 5x7 bitmap font of printable ASCII for labels on contact sheets
 * and heat maps, drawn into float images.
 */
#ifndef MT_IMAGE_FONT_H
#define MT_IMAGE_FONT_H

#include "materia/image.h"

#define MT__FONT_W 5       /* glyph width in font pixels */
#define MT__FONT_H 7       /* glyph height */
#define MT__FONT_ADVANCE 6 /* glyph width plus one column of space */

/* The 7 rows of a character, top first, bit 4 the leftmost pixel. Characters
 * outside ' '..'~' get the glyph of '?'. */
const unsigned char *mt__font_glyph(int ch);

/* Width in image pixels of s drawn at `scale` image pixels per font pixel
 * (no trailing space); 0 for an empty string. */
int mt__text_width(const char *s, int scale);

/* Draws s with its top-left corner at (x, y), each font pixel a scale x scale
 * square of colour rgb (the image's first three channels, or its one), clipped
 * to the image. */
void mt__draw_text(mt_image *img, int x, int y, const char *s, int scale, const float *rgb);

#endif
