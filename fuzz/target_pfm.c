/* Fuzz target: the PFM reader. */
#define FZ_EXT ".pfm"
#include "image_target.h"
