/* The body of the measured-data fuzz targets: mt_measured_load on the input
 * written with the suffix FZ_EXT (".brdf": the irregular text reader; any
 * other: MERL's binary one), and the data it builds evaluated. */
#ifndef MT_FUZZ_MEASURED_TARGET_H
#define MT_FUZZ_MEASURED_TARGET_H

#include "fuzz.h"
#include "measured_eval.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *path = fz_write_input(data, size, FZ_EXT);
    mt_measured *m;
    if (!path) return 0;
    m = mt_measured_load(path, NULL);
    fz_measured_eval(m);
    mt_measured_destroy(m);
    mt_measured_cache_clear(); /* the next input has the same name */
    return 0;
}

#endif
