/*
 * Running the command-line tools from a test: where they are (BUILD/bin,
 * beside BUILD/tests), one run with its output captured in the test's
 * temporary directory (support/tfiles.h), and what the captured files hold.
 */
#ifndef MT_TEST_TTOOLS_H
#define MT_TEST_TTOOLS_H

/* BUILD/bin, absolute, from the test's argv[0]; static storage. */
const char *t_tool_bindir(const char *argv0);
/* Runs "TOOL ARGS" in the directory t_tmpdir_create made, standard output to
 * out.txt and standard error to err.txt there, standard input /dev/null
 * unless ARGS redirects it; returns its exit status, -1 when it did not
 * exit. */
int t_tool_run(const char *toolname, const char *args);
/* Whether the temporary directory's file name contains text. */
int t_file_holds(const char *name, const char *text);
/* One check: TOOL ARGS exits with want and file holds text. */
void t_tool_check(const char *name, const char *toolname, const char *args, int want, const char *file,
                  const char *text);

#endif
