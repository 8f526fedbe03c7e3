/*
 * A command's output, read whole, and the table rows of a conformance run in
 * it (materia-conformance --impl prints one row per configuration and check,
 * beginning with its verdict): for tests that run a tool through the shell
 * and look for the rows it must print.
 */
#ifndef MT_TEST_TOUTPUT_H
#define MT_TEST_TOUTPUT_H

/* Runs cmd with popen; *output is its standard output (malloc'd, NUL
 * terminated; NULL when it could not run). Returns its exit status, -1 when
 * it did not exit normally or could not run. */
int t_run_output(const char *cmd, char **output);
/* Whether a line of out begins with the word verdict (PASS, FAIL, XFAIL...)
 * and contains each of the texts of what, separated by '|'. */
int t_has_row(const char *out, const char *verdict, const char *what);
/* Each of rows ("VERDICT|text|text...") is a row of out; the missing ones
 * are printed, indented. Returns 1 when all are there. */
int t_has_rows(const char *out, const char *const *rows);
/* Prints (indented) up to max lines of out that do not begin with PASS:
 * what a failed check shows of a run. */
void t_show_unpassed(const char *out, int max);

#endif
