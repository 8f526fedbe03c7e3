"""The lines of materia's query protocol (docs/PROTOCOL.md), for an
implementation written in Python: reading its input, statements that continue
over lines, the numbers and directions a query carries, the `at` keys, and
writing the answers. The implementation provides a session with two methods,

    session.query(word, args)  the answer to a query line (word one of QUERIES,
                               args the words after it)
    session.statement(text)    the answer to pbrt-v2 scene text (one or more
                               lines: a statement that ends inside [ or " goes on)

each returning one line or raising ValueError (answered `error MESSAGE`) or
Unsupported (`error unsupported: MESSAGE`, which makes materia-conformance
skip the configuration), and calls serve(session).

examples/pbrt_materials.py and examples/mitsuba3/materia_mitsuba.py are built
on it; docs/TESTING-YOUR-RENDERER.md starts a new adapter from it.
"""
import math
import os
import sys

PROTOCOL = 2  # the version of docs/PROTOCOL.md these lines follow

QUERIES = ("version", "conventions", "mode", "at", "eval", "sample", "rho", "bssrdf", "shading", "texture")

# `at KEY VALUES...`: each key and its number of values, and the defaults
AT_KEYS = {"p": 3, "n": 3, "ng": 3, "dpdu": 3, "dpdv": 3, "dndu": 3, "dndv": 3, "uv": 2, "dpdx": 3, "dpdy": 3,
           "duvdx": 2, "duvdy": 2, "flip": 1}
AT_DEFAULTS = {"p": (0.0, 0.0, 0.0), "n": (0.0, 0.0, 1.0), "ng": (0.0, 0.0, 1.0), "dpdu": (1.0, 0.0, 0.0),
               "dpdv": (0.0, 1.0, 0.0), "dndu": (0.0, 0.0, 0.0), "dndv": (0.0, 0.0, 0.0), "uv": (0.5, 0.5),
               "dpdx": (0.0, 0.0, 0.0), "dpdy": (0.0, 0.0, 0.0), "duvdx": (0.0, 0.0), "duvdy": (0.0, 0.0),
               "flip": (0.0,)}

FAILED_SAMPLE = "0 0 0 0 0 0 0 0"


class Unsupported(ValueError):
    """What the implementation does not have: `error unsupported: MESSAGE`."""


def numbers(args, n, what):
    """n finite numbers from the words args, or ValueError(what)."""
    try:
        v = [float(a) for a in args]
    except ValueError:
        v = []
    if len(v) != n or not all(math.isfinite(x) for x in v):
        raise ValueError(what)
    return v


def admit(v):
    """A query's direction by the protocol's rule: as given when its squared
    length is in (0.999, 1.001), else normalized; None for a zero direction
    (black, pdf 0, a failed sample)."""
    l2 = v[0] * v[0] + v[1] * v[1] + v[2] * v[2]
    if 0.999 < l2 < 1.001:
        return v
    if not l2 > 0 or not math.isfinite(l2):
        return None
    l = math.sqrt(l2)
    return (v[0] / l, v[1] / l, v[2] / l)


def eval_args(args):
    """`eval`'s directions (wo, wi), admitted; None when one is zero (the
    answer is then 0 0 0 0)."""
    v = numbers(args, 6, "eval: needs wox woy woz wix wiy wiz")
    wo, wi = admit(tuple(v[:3])), admit(tuple(v[3:]))
    return None if wo is None or wi is None else (wo, wi)


def sample_args(args):
    """`sample`'s (wo, uc, u1, u2), wo admitted; None when wo is zero (the
    answer is then FAILED_SAMPLE)."""
    v = numbers(args, 6, "sample: needs wox woy woz uc u1 u2")
    if not all(0 <= u < 1 for u in v[3:]):
        raise ValueError("sample: uc, u1 and u2 must be in [0, 1)")
    wo = admit(tuple(v[:3]))
    return None if wo is None else (wo, v[3], v[4], v[5])


def at(point, args):
    """The shading point after `at ARGS` (a new dict; point is not changed):
    the line is all or nothing."""
    new, i = dict(point), 0
    if not args:
        raise ValueError("at: give one or more keys")
    while i < len(args):
        k = args[i]
        if k not in AT_KEYS:
            raise ValueError('at: unknown key "%s"' % k)
        n = AT_KEYS[k]
        v = numbers(args[i + 1:i + 1 + n], n, 'at: "%s" needs %d finite numbers' % (k, n))
        if k == "flip" and v[0] not in (0.0, 1.0):
            raise ValueError("at: flip is 0 or 1")
        new[k] = tuple(v)
        i += 1 + n
    return new


def incomplete(text):
    """True while text ends inside a bracket or a quoted string: the next
    line belongs to the same statement."""
    depth, quote, comment = 0, False, False
    for c in text:
        if comment:
            comment = c != "\n"
        elif c == '"':
            quote = not quote
        elif quote:
            continue
        elif c == "#":
            comment = True
        elif c == "[":
            depth += 1
        elif c == "]":
            depth -= 1
    return quote or depth > 0


def one_line(e):
    return " ".join(str(e).split())


def answer(session, line, pending):
    """The answer to one input line (None when the line is not answered: blank,
    a comment, or inside a statement), and the statement text still open."""
    if pending is not None:
        pending += "\n" + line
        if incomplete(pending):
            return None, pending
        text = pending
    else:
        words = line.split()
        if not words or words[0].startswith("#"):
            return None, None
        if words[0] in QUERIES:
            return reply(lambda: session.query(words[0], words[1:])), None
        if incomplete(line):
            return None, line
        text = line
    return reply(lambda: session.statement(text)), None


def reply(fn):
    try:
        return fn()
    except Unsupported as e:
        return "error unsupported: %s" % one_line(e)
    except ValueError as e:
        return "error %s" % one_line(e)


def serve(session, infd=0, out=None):
    """Answers the lines of infd until its end, or until the reader of the
    answers goes away (a reproducer piped into `head`: status 0, no traceback).
    Whatever has arrived is answered and written at once: a client that keeps
    the pipe full gets large writes, one that sends a line and waits gets its
    answer."""
    out = out or sys.stdout.buffer
    try:
        return serve_lines(session, infd, out)
    except BrokenPipeError:
        # nobody reads the answers any more; stop Python's own flush at exit
        # from reporting the same closed pipe
        os.dup2(os.open(os.devnull, os.O_WRONLY), out.fileno())
        return 0


def serve_lines(session, infd, out):
    pending, rest = None, b""
    while True:
        chunk = os.read(infd, 1 << 16)
        if chunk:
            lines = (rest + chunk).split(b"\n")
            rest = lines.pop()
        else:
            lines, rest = ([rest] if rest else []), b""
        answers = []
        for raw in lines:
            a, pending = answer(session, raw.decode("utf-8", "replace").rstrip("\r"), pending)
            if a is not None:
                answers.append(a)
        if answers:
            out.write(("\n".join(answers) + "\n").encode())
            out.flush()
        if not chunk:
            break
    if pending is not None:
        out.write(b"error end of input inside a statement (unclosed bracket or string)\n")
        out.flush()
    return 0
