#!/usr/bin/env python3
"""Mitsuba 3's own chi-square test (mitsuba.chi2.ChiSquareTest) run on a
plugin of the in-process interface (include/materia/impl.h, ABI 1) through
ctypes: how often it catches the smooth errors that tests/plugin_planted.c
plants, the same plugin and configurations that bench/power.sh runs
materia's suite on (docs/TRADEOFF.md, "Detection curves").

    python3 mitsuba_detection.py PLUGIN.so CONFIG KINDS EPSS SEEDS [options]

CONFIG  a configuration by name: "matte Kd=1", "plastic default" or
        "metal default (copper)" (the pbrt-v2 statement of materia's
        catalog, conformance/impl_catalog.c), or a statement itself
        (Material "...")
KINDS   "warp pdf f none" (tests/plugin_planted.c); EPSS "0.01 0.02"

Mitsuba's settings are those of its own BSDF tests (src/bsdfs/tests in
mitsuba3: ChiSquareTest's defaults, 1e6 samples, res 101, ires 4, sample_dim
3, significance 0.01); --samples, --res, --ires, --significance change them.
The incoming directions are the suite's --quick ones (conformance/case.c:
cos theta 0.9999, 0.7, 0.03), one test each, Sidak-corrected over them
(ChiSquareTest.run's test_count), and a run is caught when any of them
rejects, as the suite counts a configuration; --wo "x,y,z" tests one
direction instead (Mitsuba's tests use (0,0,1) or normalize(1,1,1)).

Prints one line per (kind, eps) in bench/power.sh's format (tab-separated):
"mitsuba CONFIG KIND EPS caught/runs seconds", seconds of wall time.
Exit status 2 for bad usage or a plugin that cannot be loaded.
"""
import argparse
import ctypes as C
import math
import sys
import time

CATALOG = {
    # conformance/impl_catalog.c's statements for these names
    "matte Kd=1": 'Material "matte" "rgb Kd" [1 1 1]',
    "plastic default": 'Material "plastic"',
    "metal default (copper)": 'Material "metal"',
}

# conformance/case.c: the suite's --quick incoming directions (cos theta,
# phi in radians), rounded to float as the suite rounds them
QUICK_WO = [(0.9999, 0.7), (0.7, 2.0), (0.03, 4.6)]


class V3(C.Structure):
    _fields_ = [("x", C.c_double), ("y", C.c_double), ("z", C.c_double)]


MSG = C.c_char_p
SZ = C.c_size_t
CREATE = C.CFUNCTYPE(C.c_void_p, C.c_char_p, C.c_void_p, SZ)
DESTROY = C.CFUNCTYPE(None, C.c_void_p)
OPEN = C.CFUNCTYPE(C.c_int, C.c_void_p, C.c_char_p, C.POINTER(C.c_char_p), C.c_int, C.POINTER(C.c_void_p),
                   C.c_void_p, SZ)
EVAL = C.CFUNCTYPE(C.c_int, C.c_void_p, C.c_int, C.c_void_p, C.c_void_p, C.c_void_p, C.c_void_p, SZ)
SAMPLE = C.CFUNCTYPE(C.c_int, C.c_void_p, C.c_int, C.c_void_p, C.c_void_p, C.c_void_p, C.c_void_p, SZ)
CLOSE = C.CFUNCTYPE(None, C.c_void_p)


class Plugin(C.Structure):
    # include/materia/impl.h, struct mt_impl_plugin (ABI 1)
    _fields_ = [("abi", C.c_int), ("name", C.c_char_p), ("version", C.c_char_p), ("precision", C.c_char_p),
                ("conventions", C.c_char_p), ("create", CREATE), ("destroy", DESTROY), ("open", OPEN),
                ("eval", EVAL), ("sample", SAMPLE), ("close", CLOSE)]


class Impl:
    """One plugin (loaded once) and one configuration of it."""

    def __init__(self, path, arg, mode, lines):
        import numpy as np
        self.np = np
        # numpy layouts of mt_impl_v3, mt_impl_eval, mt_impl_sample
        self.v3 = np.dtype([("x", "f8"), ("y", "f8"), ("z", "f8")], align=True)
        self.ev = np.dtype([("f", "f8", 3), ("pdf", "f8")], align=True)
        self.sm = np.dtype([("wi", "f8", 3), ("f", "f8", 3), ("pdf", "f8"), ("flags", "u4")], align=True)
        assert self.v3.itemsize == 24 and self.ev.itemsize == 32 and self.sm.itemsize == 64
        self.lib = C.CDLL(path)
        entry = self.lib.mt_impl_plugin_v1
        entry.restype = C.POINTER(Plugin)
        self.p = entry().contents
        if self.p.abi != 1:
            raise RuntimeError("%s: ABI %d, this script speaks 1" % (path, self.p.abi))
        self.msg = C.create_string_buffer(1024)
        self.state = None
        if self.p.create:
            self.state = self.p.create(arg.encode() if arg is not None else None, self.msg, len(self.msg))
            if not self.state:
                raise RuntimeError("%s: create: %s" % (path, self.msg.value.decode()))
        arr = (C.c_char_p * len(lines))(*[s.encode() for s in lines])
        self.config = C.c_void_p()
        r = self.p.open(self.state, mode.encode(), arr, len(lines), C.byref(self.config), self.msg, len(self.msg))
        if r != 0:
            raise RuntimeError("%s: open: %s (status %d)" % (path, self.msg.value.decode(), r))

    def close(self):
        self.p.close(self.config)
        if self.p.destroy:
            self.p.destroy(self.state)

    def _wo(self, wo, n):
        a = self.np.empty(n, self.v3)
        a["x"], a["y"], a["z"] = wo
        return a

    def sample(self, wo, u):
        """u: float32 array (n, 3) of (uc, u1, u2); the samples' array."""
        n = len(u)
        u = self.np.ascontiguousarray(u, dtype=self.np.float32)
        out = self.np.zeros(n, self.sm)
        w = self._wo(wo, n)
        if self.p.sample(self.config, n, w.ctypes.data, u.ctypes.data, out.ctypes.data, self.msg, len(self.msg)):
            raise RuntimeError("sample: " + self.msg.value.decode())
        return out

    def pdf(self, wo, wi):
        """wi: float64 array (n, 3); the pdf of each."""
        n = len(wi)
        w = self._wo(wo, n)
        d = self.np.empty(n, self.v3)
        d["x"], d["y"], d["z"] = wi[:, 0], wi[:, 1], wi[:, 2]
        out = self.np.zeros(n, self.ev)
        if self.p.eval(self.config, n, w.ctypes.data, d.ctypes.data, out.ctypes.data, self.msg, len(self.msg)):
            raise RuntimeError("eval: " + self.msg.value.decode())
        return out["pdf"]


def adapter(mi, np, impl, wo):
    """BSDFAdapter's two functions (mitsuba/python/chi2.py) for a plugin:
    Mitsuba's si.wi is the plugin's wo, its sampled bs.wo the plugin's wi;
    a sample with zero weight (pdf 0 or f 0) counts with weight 0."""

    def sample_func(sample):
        u = np.array(sample, dtype=np.float32).T  # (n, 3): uc, u1, u2 as BSDF.sample's sample1, sample2
        s = impl.sample(wo, u)
        ok = (s["pdf"] > 0) & np.any(s["f"] != 0, axis=1)
        wi = np.where(ok[:, None], s["wi"], 0.0).astype(np.float32)
        return mi.Vector3f(np.ascontiguousarray(wi.T)), mi.Float(ok.astype(np.float32))

    def pdf_func(p):
        wi = np.array(p, dtype=np.float64).T
        return mi.Float(impl.pdf(wo, wi).astype(np.float32))

    return sample_func, pdf_func


def quick_wo():
    import numpy as np
    out = []
    for cz, phi in QUICK_WO:
        s = math.sqrt(1 - cz * cz)
        out.append(tuple(float(np.float32(v)) for v in (s * math.cos(phi), s * math.sin(phi), cz)))
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("plugin")
    ap.add_argument("config")
    ap.add_argument("kinds")
    ap.add_argument("epss")
    ap.add_argument("seeds", type=int)
    ap.add_argument("--samples", type=int, default=1000000)
    ap.add_argument("--res", type=int, default=101)
    ap.add_argument("--ires", type=int, default=32)
    ap.add_argument("--significance", type=float, default=0.01)
    ap.add_argument("--mode", default="corrected")
    ap.add_argument("--wo", default=None, help="one incoming direction x,y,z (normalized) instead of the suite's three")
    ap.add_argument("--variant", default="llvm_ad_rgb")
    ap.add_argument("--threads", type=int, default=2, help="Dr.Jit's worker threads")
    a = ap.parse_args()
    if a.seeds < 1:
        ap.error("SEEDS must be at least 1")
    statement = CATALOG.get(a.config, a.config)
    if not statement.startswith("Material"):
        ap.error("CONFIG %r: not one of %s, nor a Material statement" % (a.config, ", ".join(CATALOG)))
    try:
        epss = [float(e) for e in a.epss.split()]
    except ValueError:
        ap.error("EPSS %r: not numbers" % a.epss)
    if a.wo:
        try:
            v = [float(x) for x in a.wo.split(",")]
            if len(v) != 3:
                raise ValueError
        except ValueError:
            ap.error("--wo %r: wants x,y,z" % a.wo)
        n = math.sqrt(sum(x * x for x in v))
        wos = [tuple(x / n for x in v)]
    else:
        wos = quick_wo()
    try:
        import numpy as np
        import drjit as dr
        import mitsuba as mi
        mi.set_variant(a.variant)
    except Exception as e:  # not installed, or no such variant
        print("mitsuba_detection.py: Mitsuba 3 unavailable (%s)" % e, file=sys.stderr)
        return 3
    dr.set_thread_count(a.threads)
    for kind in a.kinds.split():
        for eps in epss:
            try:
                impl = Impl(a.plugin, "%s %g" % (kind, eps), a.mode, [statement])
            except (OSError, AttributeError, RuntimeError) as e:
                print("mitsuba_detection.py: %s" % e, file=sys.stderr)
                return 2
            t0 = time.time()
            caught = 0
            tables = {}
            for seed in range(1, a.seeds + 1):
                rejected = False
                for k, wo in enumerate(wos):
                    sf, pf = adapter(mi, np, impl, wo)
                    chi2 = mi.chi2.ChiSquareTest(domain=mi.chi2.SphericalDomain(), sample_func=sf, pdf_func=pf,
                                                 sample_dim=3, sample_count=a.samples, res=a.res, ires=a.ires,
                                                 seed=seed * len(wos) + k)
                    # the integrated pdf is the same for every seed: computed once
                    if k in tables:
                        chi2.pdf, chi2.pdf_sum, chi2.histogram_start, chi2.histogram_end = tables[k]
                    else:
                        chi2.tabulate_pdf()
                        tables[k] = (chi2.pdf, chi2.pdf_sum, chi2.histogram_start, chi2.histogram_end)
                    if not chi2.run(significance_level=a.significance, test_count=len(wos), quiet=True):
                        rejected = True
                caught += rejected
            impl.close()
            print("mitsuba\t%s\t%s\t%s\t%d/%d\t%.1f" % (a.config, kind, eps, caught, a.seeds, time.time() - t0),
                  flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
