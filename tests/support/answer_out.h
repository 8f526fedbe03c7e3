/*
 * One answer line of a protocol speaker written to standard output, flushed
 * only when no query is waiting on standard input: the pipe stays full
 * (docs/PROTOCOL.md). For the test implementations behind the protocol
 * (tests/impl_wrong.c, tests/impl_other.c), which are programs of their
 * own: a function of this header, not of a library.
 */
#ifndef T_ANSWER_OUT_H
#define T_ANSWER_OUT_H

#include <poll.h>
#include <stdio.h>

static void t_answer_out(const char *s)
{
    struct pollfd p;
    fputs(s, stdout);
    fputc('\n', stdout);
    p.fd = 0;
    p.events = POLLIN;
    if (poll(&p, 1, 0) <= 0) fflush(stdout);
}

#endif
