#!/usr/bin/env python3
"""The smallest implementation of the query protocol: it speaks the protocol
and has no material. materia-conformance --impl skips every configuration on
it (each statement is answered `error unsupported: ...`), and exits 0: the
first run of docs/TESTING-YOUR-RENDERER.md, and where an adapter of your own
starts. Replace statement() with your scene parser and answer eval and sample
from your BSDF (examples/mitsuba3/materia_mitsuba.py is a whole one).

    materia-conformance --impl 'python3 examples/empty_adapter.py' --compare none --quick
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import query_protocol as qp  # noqa: E402 (examples/query_protocol.py: the protocol's lines)


class Session:
    def __init__(self):
        self.point = dict(qp.AT_DEFAULTS)  # the shading point `at` sets

    def statement(self, text):
        """pbrt-v2 scene text: a material, a texture, ... Answer "ok" once it is
        yours; until then the suite skips the configuration."""
        raise qp.Unsupported("%s: this adapter has no materials yet" % text.split()[0])

    def query(self, word, args):
        if word == "version":
            return "protocol %d empty_adapter 0.1 precision double" % qp.PROTOCOL
        if word == "conventions":  # what your renderer does: docs/PROTOCOL.md
            return "transport radiance sample-numbers 3"
        if word == "mode":  # pbrt-v2 or corrected: materia's two behaviours; yours is one
            return "ok"
        if word == "at":
            self.point = qp.at(self.point, args)
            return "ok"
        raise qp.Unsupported("%s: no material to answer with" % word)


if __name__ == "__main__":
    sys.exit(qp.serve(Session()))
