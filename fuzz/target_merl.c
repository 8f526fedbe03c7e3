/* Fuzz target: the MERL binary BRDF reader. */
#define FZ_EXT ".binary"
#include "measured_target.h"
