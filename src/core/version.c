/* Version and precision, so that a program can check what it linked. */
#include "materia.h"

const char *mt_version(void) { return MT_VERSION; }
const char *mt_precision(void) { return MT_REAL_NAME; }
