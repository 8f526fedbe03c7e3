#!/usr/bin/env python3
"""Loads the conformance vectors (vectors/README.md) and prints, for each
mode and file, the worst relative difference between two directories of
answers (default: vectors/float and vectors/double), measured as the README
says: relative to the larger of the value and 1e-3 of the row's largest
answer. Usage: python3 vectors/compare.py [DIR_A DIR_B]"""
import csv
import os
import sys

# leading columns that are inputs, per file
INPUTS = {"eval": 8, "sample": 8, "rho": 5, "bssrdf": 2, "shading": 2, "texture": 3}


def numbers(fields):
    out = []
    for x in fields:
        try:
            out.append(float(x))
        except ValueError:
            out.append(None)  # an empty field: a value that does not exist
    return out


def worst(path_a, path_b, k):
    with open(path_a, newline="") as fa, open(path_b, newline="") as fb:
        rows_a, rows_b = list(csv.reader(fa))[1:], list(csv.reader(fb))[1:]
    if len(rows_a) != len(rows_b):
        sys.exit("%s and %s have different rows" % (path_a, path_b))
    w, where = 0.0, None
    for a, b in zip(rows_a, rows_b):
        if a[:k] != b[:k]:
            sys.exit("%s and %s: different inputs %s / %s" % (path_a, path_b, a[:k], b[:k]))
        va, vb = numbers(a[k:]), numbers(b[k:])
        scale = max([abs(v) for v in vb if v is not None] + [0.0])
        for x, y in zip(va, vb):
            if x is None or y is None:
                continue
            e = abs(x - y) / max(abs(y), 1e-3 * scale, 1e-30)
            if e > w:
                w, where = e, a[:k]
    return w, len(rows_a), where


def main():
    root = os.path.dirname(os.path.abspath(__file__))
    a = sys.argv[1] if len(sys.argv) > 2 else os.path.join(root, "float")
    b = sys.argv[2] if len(sys.argv) > 2 else os.path.join(root, "double")
    for mode in ("pbrt-v2", "corrected"):
        for name, k in INPUTS.items():
            w, n, where = worst(os.path.join(a, mode, name + ".csv"), os.path.join(b, mode, name + ".csv"), k)
            print("%-9s %-8s %5d rows  worst %.2g  at %s" % (mode, name, n, w, ",".join(where or [])))


if __name__ == "__main__":
    main()
