/*
 * Small float images for tests: made filled with one value, addressed by
 * pixel.
 */
#ifndef MT_TEST_TIMAGE_H
#define MT_TEST_TIMAGE_H

#include "materia/image.h"

/* A w x h image of nc channels, every value v; exits the test when out of
 * memory (free it with mt_image_destroy). */
mt_image t_image_make(int w, int h, int nc, float v);

/* The first channel of pixel (x, y). */
float *t_image_px(const mt_image *img, int x, int y);

#endif
