/* Fuzz target: the SPD reader (mt_spd_read), and the spectrum it reads
 * converted to RGB. */
#include <stdlib.h>
#include "fuzz.h"
#include "materia/spectrum.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    const char *path = fz_write_input(data, size, ".spd");
    double *lambda = NULL, *values = NULL;
    int n = 0;
    if (!path) return 0;
    if (mt_spd_read(path, &lambda, &values, &n, NULL) == MT_OK) {
        mt_rgb c = mt_spectrum_from_sampled(lambda, values, n);
        (void)c;
        free(lambda);
        free(values);
    }
    return 0;
}
