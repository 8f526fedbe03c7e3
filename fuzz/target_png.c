/* Fuzz target: the PNG reader. */
#define FZ_EXT ".png"
#include "image_target.h"
