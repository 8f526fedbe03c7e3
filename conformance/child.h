/*
 * A child process that speaks the query protocol on its standard input and
 * output (materia-conformance --impl). Queries go out in batches while the
 * answers come back, so the pipe stays full; every answer must arrive within
 * the timeout of the one before it. Whatever goes wrong (the child exits, is
 * killed, hangs, closes its output, answers a line longer than 1 MB) is a
 * message naming the query left unanswered; nothing here blocks for longer
 * than the timeout or lets a signal stop the suite.
 */
#ifndef CF_CHILD_H
#define CF_CHILD_H

#include <stddef.h>
#include <sys/types.h>

typedef struct cf_child {
    pid_t pid;          /* the process group leader (sh -c COMMAND), or 0 */
    int to, from;       /* its standard input and output */
    double timeout;     /* seconds allowed for each answer */
    char *in;           /* bytes read and not yet returned as answers */
    size_t in_len, in_cap;
    char *answers;      /* the last batch's answers, NUL-separated */
    size_t answers_cap;
    char msg[600];      /* what went wrong, once something has */
    int failed;
    int hung;           /* the failure was a timeout */
} cf_child;

/* Starts `sh -c command` in a process group of its own. 0, or -1 and msg. */
int cf_child_start(cf_child *c, const char *command, double timeout);

/* Sends text (n lines, each ending in '\n', each one query) and collects n
 * answers: ans[i] points at the i-th answer (without its newline), valid
 * until the next call. 0, or -1 with msg naming the first unanswered query;
 * the child is then stopped and every later call fails at once. */
int cf_child_batch(cf_child *c, const char *text, size_t len, int n, const char **ans);

/* Closes the child's input and waits (up to the timeout) for it to exit. 0
 * when it exited with status 0 and printed nothing more; else -1 and msg
 * (extra lines, a non-zero status, a signal, or no exit). Always reaps it. */
int cf_child_finish(cf_child *c);

/* Kills the child's process group (if running) and frees everything. */
void cf_child_free(cf_child *c);

#endif
