/*
 * The child process behind --impl: fork and exec `sh -c COMMAND` with two
 * pipes, then write queries and read answers at the same time (poll on both
 * ends, non-blocking), so neither side waits for the other however long the
 * batch. The child runs in its own process group so that a hung one is
 * killed with whatever it started. See child.h.
 */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>
#include "child.h"

#define MAX_LINE (1 << 20)

/* Pipes are made close-on-exec under one lock, so that a child started by
 * another thread at the same moment does not inherit this child's ends (it
 * would keep them open and hide this child's exit). */
static pthread_mutex_t spawn_lock = PTHREAD_MUTEX_INITIALIZER;

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void sleep_ms(int ms)
{
    struct timespec t;
    t.tv_sec = ms / 1000;
    t.tv_nsec = (long)(ms % 1000) * 1000000L;
    nanosleep(&t, NULL);
}

static void cloexec(int fd)
{
    fcntl(fd, F_SETFD, fcntl(fd, F_GETFD) | FD_CLOEXEC);
}

static void nonblock(int fd)
{
    fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) | O_NONBLOCK);
}

int cf_child_start(cf_child *c, const char *command, double timeout)
{
    int a[2], b[2];
    struct sigaction sa;
    memset(c, 0, sizeof *c);
    c->to = c->from = -1;
    c->timeout = timeout;
    /* a child that stops reading makes write() fail with EPIPE, not kill us */
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = SIG_IGN;
    sigaction(SIGPIPE, &sa, NULL);
    pthread_mutex_lock(&spawn_lock);
    if (pipe(a)) {
        pthread_mutex_unlock(&spawn_lock);
        snprintf(c->msg, sizeof c->msg, "could not make a pipe: %s", strerror(errno));
        return c->failed = -1;
    }
    if (pipe(b)) {
        close(a[0]);
        close(a[1]);
        pthread_mutex_unlock(&spawn_lock);
        snprintf(c->msg, sizeof c->msg, "could not make a pipe: %s", strerror(errno));
        return c->failed = -1;
    }
    cloexec(a[0]);
    cloexec(a[1]);
    cloexec(b[0]);
    cloexec(b[1]);
    c->pid = fork();
    if (c->pid == 0) {
        /* only async-signal-safe calls until exec */
        setpgid(0, 0);
        dup2(a[0], 0);
        dup2(b[1], 1);
        execl("/bin/sh", "sh", "-c", command, (char *)NULL);
        _exit(127);
    }
    if (c->pid > 0) setpgid(c->pid, c->pid); /* either side may run first */
    pthread_mutex_unlock(&spawn_lock);
    close(a[0]);
    close(b[1]);
    if (c->pid < 0) {
        close(a[1]);
        close(b[0]);
        c->pid = 0;
        snprintf(c->msg, sizeof c->msg, "could not fork: %s", strerror(errno));
        return c->failed = -1;
    }
    c->to = a[1];
    c->from = b[0];
    nonblock(c->to);
    nonblock(c->from);
    return 0;
}

/* Reaps the child, waiting up to `wait` seconds; describes how it ended. */
static int reap(cf_child *c, double wait, char *how, size_t n)
{
    double t0 = now();
    int status;
    if (!c->pid) {
        snprintf(how, n, "had already ended");
        return 0;
    }
    for (;;) {
        pid_t r = waitpid(c->pid, &status, WNOHANG);
        if (r == c->pid) break;
        if (r < 0 && errno != EINTR) {
            snprintf(how, n, "could not be waited for: %s", strerror(errno));
            c->pid = 0;
            return -1;
        }
        if (now() - t0 >= wait) {
            kill(-c->pid, SIGKILL);
            waitpid(c->pid, &status, 0);
            c->pid = 0;
            snprintf(how, n, "did not exit within %g s (killed)", wait);
            return -1;
        }
        sleep_ms(2);
    }
    c->pid = 0;
    if (WIFEXITED(status)) {
        int x = WEXITSTATUS(status);
        /* the shell reports its command's death by signal N as status 128 + N */
        if (x > 128 && x < 128 + 32)
            snprintf(how, n, "exited with status %d (the shell's words for signal %d%s)", x, x - 128,
                     x - 128 == SIGSEGV || x - 128 == SIGABRT || x - 128 == SIGBUS || x - 128 == SIGFPE ? ": it crashed" : "");
        else
            snprintf(how, n, "exited with status %d", x);
        return WEXITSTATUS(status) ? -1 : 0;
    }
    if (WIFSIGNALED(status)) {
        snprintf(how, n, "was killed by signal %d%s", WTERMSIG(status),
                 WTERMSIG(status) == SIGSEGV || WTERMSIG(status) == SIGABRT || WTERMSIG(status) == SIGBUS ||
                         WTERMSIG(status) == SIGFPE
                     ? " (it crashed)"
                     : "");
        return -1;
    }
    snprintf(how, n, "ended with status %d", status);
    return -1;
}

static void close_fds(cf_child *c)
{
    if (c->to >= 0) close(c->to);
    if (c->from >= 0) close(c->from);
    c->to = c->from = -1;
}

/* The k-th line of text (0-based), quoted, shortened to fit. */
static void quote_line(const char *text, size_t len, int k, char *out, size_t n)
{
    size_t i = 0, e;
    int line = 0;
    while (i < len && line < k) {
        if (text[i++] == '\n') line++;
    }
    e = i;
    while (e < len && text[e] != '\n') e++;
    if (e - i > 160)
        snprintf(out, n, "\"%.160s...\"", text + i);
    else
        snprintf(out, n, "\"%.*s\"", (int)(e - i), text + i);
}

static int append(char **buf, size_t *cap, size_t used, const char *src, size_t n)
{
    if (used + n + 1 > *cap) {
        size_t nc = *cap ? *cap : 4096;
        char *p;
        while (nc < used + n + 1) nc *= 2;
        if (!(p = realloc(*buf, nc))) return -1;
        *buf = p;
        *cap = nc;
    }
    memcpy(*buf + used, src, n);
    (*buf)[used + n] = 0;
    return 0;
}

static int stop_with(cf_child *c, const char *text, size_t len, int k, const char *what)
{
    char q[200], how[120];
    quote_line(text, len, k, q, sizeof q);
    close_fds(c);
    if (c->pid) {
        if (c->hung) kill(-c->pid, SIGKILL);
        reap(c, c->hung ? 1 : c->timeout, how, sizeof how);
        if (c->hung)
            snprintf(c->msg, sizeof c->msg, "%s %s", what, q);
        else
            snprintf(c->msg, sizeof c->msg, "%s %s (it %s)", what, q, how);
    } else {
        snprintf(c->msg, sizeof c->msg, "%s %s", what, q);
    }
    c->failed = -1;
    return -1;
}

int cf_child_batch(cf_child *c, const char *text, size_t len, int n, const char **ans)
{
    size_t sent = 0, used = 0, *off = NULL;
    int got = 0, i;
    double last = now();
    if (c->failed) return -1;
    if (c->in_len) { /* left over from the batch before: more lines than queries */
        char first[120], how[120];
        size_t e = 0;
        while (e < c->in_len && c->in[e] != '\n' && e < 100) e++;
        snprintf(first, sizeof first, "\"%.*s\"", (int)e, c->in);
        close_fds(c);
        if (c->pid) kill(-c->pid, SIGKILL);
        reap(c, 1, how, sizeof how);
        snprintf(c->msg, sizeof c->msg, "printed an extra line %s after its last answer, not the answer to any query", first);
        return c->failed = -1;
    }
    if (!(off = malloc(((size_t)n + 1) * sizeof *off))) {
        snprintf(c->msg, sizeof c->msg, "out of memory");
        return c->failed = -1;
    }
    while (got < n) {
        struct pollfd fds[2];
        int nf = 0, r, wi = -1, ri;
        double left = c->timeout - (now() - last);
        if (left <= 0) {
            char what[96];
            free(off);
            c->hung = 1;
            snprintf(what, sizeof what, "hung: no answer within %g s to query %d of %d,", c->timeout, got + 1, n);
            return stop_with(c, text, len, got, what);
        }
        if (sent < len && c->to >= 0) {
            fds[nf].fd = c->to;
            fds[nf].events = POLLOUT;
            wi = nf++;
        }
        fds[nf].fd = c->from;
        fds[nf].events = POLLIN;
        ri = nf++;
        r = poll(fds, (nfds_t)nf, (int)(left * 1000) + 1);
        if (r < 0) {
            if (errno == EINTR) continue;
            free(off);
            return stop_with(c, text, len, got, "poll failed while waiting for the answer to");
        }
        if (r == 0) continue; /* the timeout is checked above */
        if (wi >= 0 && fds[wi].revents) {
            size_t chunk = len - sent > 65536 ? 65536 : len - sent;
            ssize_t w = write(c->to, text + sent, chunk);
            if (w > 0) {
                sent += (size_t)w;
            } else if (w < 0 && errno != EAGAIN && errno != EINTR) {
                /* it closed its input: read what it still answers */
                close(c->to);
                c->to = -1;
            }
        }
        if (fds[ri].revents) {
            char buf[65536];
            ssize_t rd = read(c->from, buf, sizeof buf);
            size_t k, start = 0;
            if (rd < 0) {
                if (errno == EAGAIN || errno == EINTR) continue;
                free(off);
                return stop_with(c, text, len, got, "could not read the answer to");
            }
            if (rd == 0) {
                char what[96];
                free(off);
                snprintf(what, sizeof what, "ended its output after %d of %d answers; unanswered:", got, n);
                if (c->in_len) snprintf(what, sizeof what, "ended its output inside an answer (no newline); unanswered:");
                return stop_with(c, text, len, got, what);
            }
            if (append(&c->in, &c->in_cap, c->in_len, buf, (size_t)rd)) {
                free(off);
                return stop_with(c, text, len, got, "out of memory reading the answer to");
            }
            c->in_len += (size_t)rd;
            /* complete lines become answers; the rest waits for more
             * (memchr: a batched answer is thousands of bytes) */
            for (k = 0; k < c->in_len; ++k) {
                const char *nl = memchr(c->in + k, '\n', c->in_len - k);
                if (!nl) break;
                k = (size_t)(nl - c->in);
                if (got < n) {
                    size_t l = k - start;
                    if (l && c->in[start + l - 1] == '\r') l--;
                    off[got] = used;
                    if (append(&c->answers, &c->answers_cap, used, c->in + start, l)) {
                        free(off);
                        return stop_with(c, text, len, got, "out of memory reading the answer to");
                    }
                    used += l + 1;
                    got++;
                    last = now();
                    start = k + 1;
                } else {
                    break;
                }
            }
            memmove(c->in, c->in + start, c->in_len - start);
            c->in_len -= start;
            if (c->in_len > MAX_LINE) {
                free(off);
                return stop_with(c, text, len, got, "answered a line longer than 1 MB to");
            }
        }
    }
    for (i = 0; i < n; ++i) ans[i] = c->answers + off[i];
    free(off);
    return 0;
}

int cf_child_finish(cf_child *c)
{
    double t0 = now();
    char extra[120] = "", how[120];
    size_t extra_len = 0;
    int st;
    if (c->failed) {
        cf_child_free(c);
        return -1;
    }
    if (c->to >= 0) close(c->to);
    c->to = -1;
    extra_len = c->in_len;
    if (c->in_len) snprintf(extra, sizeof extra, "%.100s", c->in);
    /* drain what it prints before it exits: all of it is extra */
    while (c->from >= 0 && now() - t0 < c->timeout) {
        struct pollfd p;
        char buf[4096];
        ssize_t rd;
        p.fd = c->from;
        p.events = POLLIN;
        if (poll(&p, 1, 20) <= 0) continue;
        rd = read(c->from, buf, sizeof buf);
        if (rd == 0) break;
        if (rd < 0) {
            if (errno == EAGAIN || errno == EINTR) continue;
            break;
        }
        if (!extra_len) snprintf(extra, sizeof extra, "%.*s", (int)(rd > 100 ? 100 : rd), buf);
        extra_len += (size_t)rd;
    }
    close_fds(c);
    st = reap(c, fmax(0.0, c->timeout - (now() - t0)) + 0.05, how, sizeof how);
    {
        char *nl = strchr(extra, '\n');
        if (nl) *nl = 0;
    }
    if (extra_len)
        snprintf(c->msg, sizeof c->msg, "printed %zu bytes more than its answers (\"%s\"...); at the end of its input it %s",
                 extra_len, extra, how);
    else if (st)
        snprintf(c->msg, sizeof c->msg, "at the end of its input it %s", how);
    cf_child_free(c);
    return extra_len || st ? -1 : 0;
}

void cf_child_free(cf_child *c)
{
    close_fds(c);
    if (c->pid) {
        int status;
        kill(-c->pid, SIGKILL);
        waitpid(c->pid, &status, 0);
        c->pid = 0;
    }
    free(c->in);
    free(c->answers);
    c->in = c->answers = NULL;
    c->in_len = c->in_cap = c->answers_cap = 0;
}
