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
/* Runs cmd and checks (t_check, named name) that it exits with status and
 * prints each of rows (NULL-terminated, as t_has_rows); when not, shows the
 * rows that did not pass. Returns 1 when it did; *output, when output is not
 * NULL, keeps the output (malloc'd, or NULL) for further checks. */
int t_check_run(const char *name, const char *cmd, int status, const char *const *rows, char **output);
/* The rows of a conformance run: its output after the three lines of its
 * header. */
const char *t_rows_of(const char *out);
/* The rows' verdicts: each row up to its kind (physics, agreement), the
 * summary lines whole, the lines under a row left out (malloc'd). Two runs
 * with the same verdicts whose statistics differ in the last digits (a
 * double implementation reading the suite's 9-digit floats) compare equal. */
char *t_verdicts_of(const char *rows);
/* Whether two conformance runs (whole outputs, a run in this process first)
 * agree: in a float build their rows value for value; in a double build
 * their verdicts, since a double implementation behind the text protocol
 * reads the suite's float inputs from their 9 digits, which name the float
 * but are not its value, so its statistics differ in the last digits. */
int t_same_runs(const char *self, const char *other);

#endif
