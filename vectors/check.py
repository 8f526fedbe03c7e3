#!/usr/bin/env python3
"""Checks a program that speaks the query protocol (docs/PROTOCOL.md) against
the published conformance vectors: sends each selected configuration's
statements, points and queries (vectors/README.md, "The session") and
compares the answers with materia's, as the README's tolerances say.

    python3 vectors/check.py --impl 'COMMAND' [--only REGEX] [--skip REGEX]
                             [--precision float|double] [--files eval,sample,...]
                             [--tolerance T] [--data DIR]

REGEX is a POSIX extended regular expression, the dialect of every --only of
materia's tools (materia-conformance's too): a Python-only construct (a
lookahead "(?...", "\\d", a lazy "*?") is a usage error, not a silent
difference. --only selects the configurations whose name matches, --skip
leaves out those whose name matches.

Prints one line per mode and file, "PASS ..." or "FAIL ..." with the worst
row (query, expected, got), and exits 0 when everything passed, 1 when a
check failed, 2 on a usage error (a REGEX that selects no configuration
too)."""
import argparse
import csv
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.abspath(__file__))
INPUTS = {"eval": 8, "sample": 8, "rho": 5, "bssrdf": 2, "shading": 2, "texture": 3}
KEYS = [("p", 3), ("n", 3), ("ng", 3), ("dpdu", 3), ("dpdv", 3), ("dndu", 3), ("dndv", 3), ("uv", 2),
        ("dpdx", 3), ("dpdy", 3), ("duvdx", 2), ("duvdy", 2), ("flip", 1)]


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.reader(f))[1:]


def at_line(point):
    words, i = ["at"], 1
    for key, n in KEYS:
        words += [key] + point[i:i + n]
        i += n
    return " ".join(words)


def query(name, row, k):
    """The protocol line of a row, and the answer the row expects."""
    if name == "bssrdf":
        return "bssrdf", "none" if row[2] == "0" else " ".join(row[3:])
    if name == "texture":
        return 'texture "%s"' % row[2], " ".join(v for v in row[4:] if v != "")
    return name + " " + " ".join(row[2:k]), " ".join(row[k:])


def difference(got, want):
    """The README's measure: relative to the larger of the value and 1e-3 of
    the row's largest answer; words (none, flags) must be equal."""
    g, w = got.split(), want.split()
    if len(g) != len(w):
        return float("inf")
    try:
        gv, wv = [float(x) for x in g], [float(x) for x in w]
    except ValueError:
        return 0.0 if g == w else float("inf")
    scale = max([abs(x) for x in wv] + [0.0])
    worst = 0.0
    for x, y in zip(gv, wv):
        if x != x:
            return float("inf")
        worst = max(worst, abs(x - y) / max(abs(y), 1e-3 * scale, 1e-300))
    return worst


# POSIX character classes, inside a bracket expression, as Python writes them
ERE_CLASSES = {"alpha": "a-zA-Z", "digit": "0-9", "alnum": "a-zA-Z0-9", "upper": "A-Z", "lower": "a-z",
               "space": " \\t\\n\\r\\f\\v", "blank": " \\t", "xdigit": "0-9A-Fa-f",
               "punct": re.escape("!\"#$%&'()*+,-./:;<=>?@[\\]^_`{|}~")}


def ere(pattern, option):
    """The Python regular expression of a POSIX extended one, or a usage
    error naming what is not ERE: the same dialect as regcomp(REG_EXTENDED),
    which materia-conformance uses (whether a name matches does not depend
    on ERE's leftmost-longest rule)."""
    bad = re.search(r"\(\?|\\[dDwWsSbBAZzGpPNuUx0-9]|[*+?}][?+]", pattern)
    if bad:
        raise ValueError("%s: %r is not a POSIX extended regular expression (%r at %d: "
                         "lookaheads, \\d-style escapes, back-references and lazy quantifiers are "
                         "Python's; use --only and --skip)" % (option, pattern, bad.group(0), bad.start()))
    py = re.sub(r"\[:([a-z]+):\]", lambda m: ERE_CLASSES.get(m.group(1), m.group(0)), pattern)
    try:
        return re.compile(py)
    except re.error as e:
        raise ValueError("%s: %r is not a regular expression: %s" % (option, pattern, e))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--impl", required=True, help="the command line of the program to check")
    ap.add_argument("--only", default="", help="configurations whose name matches this POSIX extended "
                    "regular expression (default: all)")
    ap.add_argument("--skip", default=None, help="leave out configurations whose name matches this POSIX "
                    "extended regular expression (default: none)")
    ap.add_argument("--precision", default="double", choices=["float", "double"])
    ap.add_argument("--files", default="eval,sample", help="which query files (default eval,sample)")
    ap.add_argument("--tolerance", type=float, default=1e-6)
    ap.add_argument("--data", default=os.path.join(ROOT, "data"),
                    help="the directory of the files the statements name as @DATA@ (default vectors/data)")
    a = ap.parse_args()
    try:
        only = ere(a.only, "--only")
        skip = ere(a.skip, "--skip") if a.skip is not None else None
    except ValueError as e:
        sys.stderr.write("check.py: %s\n" % e)
        return 2
    data = os.path.abspath(a.data)
    with open(os.path.join(ROOT, "configs.tsv"), newline="") as f:
        configs = {r["id"]: r for r in csv.DictReader(f, delimiter="\t")}
    points = {r[0]: r for r in read_csv(os.path.join(ROOT, "points.csv"))}
    chosen = {c for c, r in configs.items() if only.search(r["name"]) and not (skip and skip.search(r["name"]))}
    selected = len(chosen)
    for c in sorted(chosen, key=int):
        # a configuration whose data file is missing (the MERL table is not
        # published: materia-conformance --write-data DIR writes it) is skipped
        r = configs[c]
        r["statements"] = r["statements"].replace("@DATA@", data)
        missing = [m for m in re.findall(r'"([^"]*)"', r["statements"]) if m.startswith(data + "/")
                   and not os.path.exists(m)]
        if missing:
            print("SKIP %s: %s is missing (materia-conformance --write-data DIR, then --data DIR)"
                  % (r["name"], missing[0]))
            chosen.discard(c)
    files = a.files.split(",")
    if not chosen or any(f not in INPUTS for f in files):
        sys.stderr.write("check.py: %s\n" % ("--files takes " + ",".join(INPUTS) if chosen
                                             else "--only %r%s selects no configuration" % (a.only, " --skip %r" % a.skip if a.skip else "")
                                             if not selected
                                             else "every selected configuration was skipped"))
        return 2
    failed = 0
    for mode in ("pbrt-v2", "corrected"):
        for name in files:
            rows = [r for r in read_csv(os.path.join(ROOT, a.precision, mode, name + ".csv")) if r[0] in chosen]
            worst, where, bad = 0.0, None, 0
            # one session (one run of the program) per configuration: a fresh state
            for c in sorted({r[0] for r in rows}, key=int):
                lines, expect, current = ["mode " + mode, configs[c]["statements"]], [None, None], None
                for r in rows:
                    if r[0] != c:
                        continue
                    if r[1] != current:
                        current = r[1]
                        lines.append(at_line(points[r[1]]))
                        expect.append(None)
                        if configs[c]["at"]:
                            # the configuration's own fields, over the point's
                            lines.append("at " + configs[c]["at"])
                            expect.append(None)
                    q, want = query(name, r, INPUTS[name])
                    lines.append(q)
                    expect.append(want)
                run = subprocess.run(a.impl, shell=True, input="\n".join(lines) + "\n", capture_output=True, text=True)
                answers = run.stdout.split("\n")
                for i, (line, want) in enumerate(zip(lines, expect)):
                    got = answers[i] if i < len(answers) else "(no answer)"
                    if want is None:
                        want, d = "ok", 0.0 if got == "ok" else float("inf")
                    else:
                        d = difference(got, want)
                    if d > a.tolerance:
                        bad += 1
                    if d > worst or where is None:
                        worst, where = d, (configs[c]["name"] + ": " + line, want, got)
            label = "vectors %s %s/%s (%d configurations, %d queries)" % (
                a.precision, mode, name, len({r[0] for r in rows}), len(rows))
            if bad:
                failed += 1
                print("FAIL %s: %d beyond %g, worst %.3g\n  query    %s\n  expected %s\n  got      %s"
                      % (label, bad, a.tolerance, worst, where[0], where[1], where[2]))
            else:
                print("PASS %s: worst relative difference %.3g" % (label, worst))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
