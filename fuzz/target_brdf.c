/* Fuzz target: the irregular measured BRDF reader (.brdf text). */
#define FZ_EXT ".brdf"
#include "measured_target.h"
