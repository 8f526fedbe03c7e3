/*
 * materia's own BSDFs as a plugin (include/materia/impl.h), for a program
 * that links it: mt_impl_run_suite(mt_materia_plugin(), argc, argv).
 */
#ifndef MATERIA_PLUGIN_H
#define MATERIA_PLUGIN_H

#include "materia/impl.h"

const mt_impl_plugin *mt_materia_plugin(void);

#endif
