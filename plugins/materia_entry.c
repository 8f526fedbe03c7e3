/*
 * The entry point of build/<precision>/plugins/materia_plugin.so: the one
 * symbol a plugin exports (include/materia/impl.h), kept apart from the
 * plugin itself so that a program (or another plugin, tests/plugin_planted.c)
 * can link materia_plugin.c without it.
 */
#include "materia/real.h"
#include "materia_plugin.h"

MT_API const mt_impl_plugin *mt_impl_plugin_v1(void);
const mt_impl_plugin *mt_impl_plugin_v1(void) { return mt_materia_plugin(); }
