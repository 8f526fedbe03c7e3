/*
 * The suite's library entry point, proven: a program that links a plugin
 * (materia's own, plugins/materia_plugin.c) and runs the suite on it with
 * its own command-line options, as an author's test program would:
 *
 *   return mt_impl_run_suite(my_plugin(), argc, argv);
 *
 * tests/test_plugin.c runs it and sets its rows against --impl-inprocess.
 */
#include "../plugins/materia_plugin.h"

int main(int argc, char **argv) { return mt_impl_run_suite(mt_materia_plugin(), argc, argv); }
