/* The body of the image fuzz targets: mt_image_read_mode in both modes on
 * the input written with the suffix FZ_EXT (which picks the reader). */
#ifndef MT_FUZZ_IMAGE_TARGET_H
#define MT_FUZZ_IMAGE_TARGET_H

#include "fuzz.h"
#include "materia/image.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *path = fz_write_input(data, size, FZ_EXT);
    mt_image img;
    int k;
    if (!path) return 0;
    for (k = 0; k < 2; ++k)
        if (mt_image_read_mode(path, k ? MT_MODE_CORRECTED : MT_MODE_PBRT_V2, &img, NULL) == MT_OK)
            mt_image_destroy(&img);
    return 0;
}

#endif
