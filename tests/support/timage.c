/* Small float images for tests. */
#include <stdio.h>
#include <stdlib.h>
#include "support/timage.h"

mt_image t_image_make(int w, int h, int nc, float v)
{
    mt_image img;
    size_t k;
    if (mt_image_create(&img, w, h, nc, NULL) != MT_OK) {
        fprintf(stderr, "out of memory for a %d x %d test image\n", w, h);
        exit(1);
    }
    for (k = 0; k < (size_t)w * (size_t)h * (size_t)nc; ++k) img.data[k] = v;
    return img;
}

float *t_image_px(const mt_image *img, int x, int y)
{
    return img->data + ((size_t)y * (size_t)img->width + (size_t)x) * (size_t)img->channels;
}
