/* Fuzz target: the EXR reader. */
#define FZ_EXT ".exr"
#include "image_target.h"
