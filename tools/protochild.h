/*
 * Shared by the command-line tools (included, not compiled on its own): a
 * program that speaks the query protocol (docs/PROTOCOL.md), run as a child
 * process through `sh -c COMMAND`, with its standard input and output on
 * pipes. Answers are read with a timeout, so a child that hangs is reported
 * rather than waited for; one that exits is reported with the query it left
 * unanswered.
 */
#ifndef MT_TOOLS_PROTOCHILD_H
#define MT_TOOLS_PROTOCHILD_H

#include <errno.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

typedef struct pc_child {
    pid_t pid;
    int to_child, from_child; /* our ends of the pipes */
    char buf[1 << 16];        /* bytes read and not yet returned as lines */
    size_t len;
    int timeout_ms; /* per answer */
} pc_child;

/* Children still running when the program exits (an error after which it
 * exits at once) are killed then. */
static pid_t pc_live[8];

static void pc_kill_live(void)
{
    int i, status;
    for (i = 0; i < 8; ++i)
        if (pc_live[i] > 0) {
            kill(pc_live[i], SIGKILL);
            waitpid(pc_live[i], &status, 0);
            pc_live[i] = 0;
        }
}

static void pc_track(pid_t pid, pid_t was)
{
    static int registered;
    int i;
    if (!registered) registered = atexit(pc_kill_live) == 0;
    for (i = 0; i < 8; ++i)
        if (pc_live[i] == was) {
            pc_live[i] = pid;
            return;
        }
}

static int pc_start(pc_child *c, const char *command, int timeout_ms, char *err, size_t errsize)
{
    int in[2], out[2];
    memset(c, 0, sizeof *c);
    c->pid = -1;
    c->timeout_ms = timeout_ms;
    /* a child that exits makes our writes fail with EPIPE, not kill us */
    signal(SIGPIPE, SIG_IGN);
    if (pipe(in) != 0) {
        snprintf(err, errsize, "pipe: %s", strerror(errno));
        return 0;
    }
    if (pipe(out) != 0) {
        snprintf(err, errsize, "pipe: %s", strerror(errno));
        close(in[0]);
        close(in[1]);
        return 0;
    }
    c->pid = fork();
    if (c->pid < 0) {
        snprintf(err, errsize, "fork: %s", strerror(errno));
        close(in[0]), close(in[1]), close(out[0]), close(out[1]);
        return 0;
    }
    if (c->pid == 0) {
        dup2(in[0], 0);
        dup2(out[1], 1);
        close(in[0]), close(in[1]), close(out[0]), close(out[1]);
        execl("/bin/sh", "sh", "-c", command, (char *)NULL);
        _exit(127);
    }
    pc_track(c->pid, 0);
    close(in[0]);
    close(out[1]);
    c->to_child = in[1];
    c->from_child = out[0];
    return 1;
}

static int pc_write(pc_child *c, const char *text, size_t n, char *err, size_t errsize)
{
    while (n > 0) {
        ssize_t w = write(c->to_child, text, n);
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) {
            snprintf(err, errsize, "cannot write to it (%s): it exited?", w < 0 ? strerror(errno) : "no progress");
            return 0;
        }
        text += w;
        n -= (size_t)w;
    }
    return 1;
}

/* One answer line, without its newline (and a carriage return before it). */
static int pc_read_line(pc_child *c, char *line, size_t size, char *err, size_t errsize)
{
    for (;;) {
        char *nl = memchr(c->buf, '\n', c->len);
        struct pollfd p;
        ssize_t r;
        int k;
        if (nl) {
            size_t n = (size_t)(nl - c->buf), keep = n;
            if (keep && c->buf[keep - 1] == '\r') keep--;
            if (keep >= size) keep = size - 1;
            memcpy(line, c->buf, keep);
            line[keep] = 0;
            memmove(c->buf, nl + 1, c->len - n - 1);
            c->len -= n + 1;
            return 1;
        }
        if (c->len == sizeof c->buf) {
            snprintf(err, errsize, "an answer longer than %zu bytes", sizeof c->buf);
            return 0;
        }
        p.fd = c->from_child;
        p.events = POLLIN;
        k = poll(&p, 1, c->timeout_ms);
        if (k < 0 && errno == EINTR) continue;
        if (k == 0) {
            snprintf(err, errsize, "no answer within %d s (it hangs?)", c->timeout_ms / 1000);
            return 0;
        }
        r = read(c->from_child, c->buf + c->len, sizeof c->buf - c->len);
        if (r < 0 && errno == EINTR) continue;
        if (r <= 0) {
            snprintf(err, errsize, "it closed its output (exited?) before answering");
            return 0;
        }
        c->len += (size_t)r;
    }
}

/* Closes its input (a protocol program ends at the end of its input) and
 * waits for it; a child that does not end within the timeout is killed. */
static void pc_stop(pc_child *c)
{
    int i, status;
    if (c->pid <= 0) return;
    close(c->to_child);
    close(c->from_child);
    for (i = 0; i < c->timeout_ms / 10 + 1; ++i) {
        if (waitpid(c->pid, &status, WNOHANG) == c->pid) {
            pc_track(0, c->pid);
            c->pid = -1;
            return;
        }
        {
            struct timespec ts = {0, 10000000};
            nanosleep(&ts, NULL);
        }
    }
    kill(c->pid, SIGKILL);
    waitpid(c->pid, &status, 0);
    pc_track(0, c->pid);
    c->pid = -1;
}

#endif
