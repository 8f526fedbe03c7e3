#!/usr/bin/env python3
"""Mitsuba 3's BSDFs behind materia's query protocol (docs/PROTOCOL.md), so that
materia-conformance --impl can test them:

    materia-conformance --impl 'python3 examples/mitsuba3/materia_mitsuba.py' --compare none

pbrt-v2 statements are mapped to Mitsuba plugins (materials.py says which, with
which conversion, and what is `error unsupported: ...`); `eval` and `sample`
call the plugin's BSDF.eval_pdf and BSDF.sample (scalar_rgb variant, single
precision) with a SurfaceInteraction3f at the query's shading point.

    python3 materia_mitsuba.py [--transport radiance|importance] [--microfacet beckmann|ggx] [--dir DIR]

--transport sets the BSDFContext's TransportMode (default radiance, Mitsuba's
own default) and the convention the `conventions` query declares.
--microfacet is the distribution pbrt-v2's Blinn lobes (plastic, metal, uber)
become (default beckmann). --dir is where relative file names (spectra,
Include) are found.

Conventions: Mitsuba's sample(ctx, si, sample1, sample2) chooses the lobe with
sample1 (dielectric's Fresnel choice, plastic's specular or diffuse, blendbsdf's
and mask's child, rescaled before the child sees it) and draws the direction
from sample2 alone: uc -> sample1, (u1, u2) -> sample2, pbrt-v2's three numbers
("sample-numbers 3"). Mitsuba's eval() is f times |cos theta| of the outgoing
direction; the protocol's f is without it, so the adapter divides by the
cosine of the direction as Mitsuba received it (a float), and answers f = 0
where that cosine is 0. A sample's f is its weight times its pdf over that
cosine (the weight is f |cos| / pdf); a sample whose weight is 0 in every
channel is failed: Mitsuba marks an invalid sample so, and its own chi2 test
(mitsuba.chi2.BSDFAdapter) drops such samples too.
"""
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path[:0] = [HERE, os.path.dirname(HERE)]  # its modules, and examples/query_protocol.py

import drjit as dr  # noqa: E402
import mitsuba as mi  # noqa: E402

mi.set_variant("scalar_rgb")

import materials  # noqa: E402
import query_protocol as qp  # noqa: E402
from pbrt_scene import InputError, Missing, State, Unsupported  # noqa: E402


# Mitsuba's BSDFFlags -> pbrt-v2's BxDFType bits (reflection 1, transmission 2,
# diffuse 4, glossy 8, specular 16). Null (mask's pass-through) is a delta
# transmission with eta 1, as pbrt-v2's uber builds it.
F = mi.BSDFFlags
REFL = int(F.DiffuseReflection) | int(F.GlossyReflection) | int(F.DeltaReflection)
TRANS = int(F.DiffuseTransmission) | int(F.GlossyTransmission) | int(F.DeltaTransmission) | int(F.Null)
DIFF, GLOSSY = int(F.Diffuse), int(F.Glossy)
DELTA = int(F.DeltaReflection) | int(F.DeltaTransmission) | int(F.Null) | int(F.Delta1D)


def pbrt_flags(t):
    return ((1 if t & REFL else 0) | (2 if t & TRANS else 0) | (4 if t & DIFF else 0) | (8 if t & GLOSSY else 0) |
            (16 if t & DELTA else 0))


# ---- vectors -------------------------------------------------------------------------
def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def normalize(a):
    l = math.sqrt(dot(a, a))
    return (a[0] / l, a[1] / l, a[2] / l) if l > 0 else None


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def fmt(values):
    return " ".join("%.9g" % v for v in values)


def mitsuba_errors(fn, *args):
    """fn(*args), Mitsuba's exceptions (a plugin refusing its parameters)
    turned into error answers."""
    try:
        return fn(*args)
    except RuntimeError as e:
        raise InputError("Mitsuba: %s" % qp.one_line(e))


# ---- the session ---------------------------------------------------------------------
class Session:
    def __init__(self, transport, directory):
        self.transport = transport
        mode = mi.TransportMode.Importance if transport == "importance" else mi.TransportMode.Radiance
        self.ctx = mi.BSDFContext(mode)
        self.dir = directory
        self.state = State(materials.make_material, materials.make_texture, self.resolve)
        self.point = dict(qp.AT_DEFAULTS)
        self.point_version = 0
        self.set_frame()
        self.cache = {}  # (material, point version or None) -> loaded BSDF
        self.varies = {}  # material -> whether its BSDF depends on the point

    def resolve(self, name):
        return name if os.path.isabs(name) else os.path.join(self.dir, name)

    def set_frame(self):
        """The shading frame as Mitsuba's compute_shading_frame() makes it: n
        normalized, s = dpdu made perpendicular to n and normalized, t = n x s;
        and the SurfaceInteraction3f the plugins see."""
        pt = self.point
        n = normalize(pt["n"]) or (0.0, 0.0, 1.0)
        d = pt["dpdu"]
        k = dot(n, d)
        s = normalize((d[0] - k * n[0], d[1] - k * n[1], d[2] - k * n[2]))
        if s is None:  # dpdu along n: any perpendicular (Mitsuba's coordinate_system)
            s = normalize(cross(n, (1.0, 0.0, 0.0) if abs(n[0]) < 0.9 else (0.0, 1.0, 0.0)))
        t = cross(n, s)
        self.frame = (s, t, n)
        si = dr.zeros(mi.SurfaceInteraction3f)
        si.p = mi.Point3f(*pt["p"])
        si.n = mi.Normal3f(*(normalize(pt["ng"]) or n))
        si.sh_frame = mi.Frame3f(mi.Vector3f(*s), mi.Vector3f(*t), mi.Vector3f(*n))
        si.uv = mi.Point2f(*pt["uv"])
        si.dp_du, si.dp_dv = mi.Vector3f(*pt["dpdu"]), mi.Vector3f(*pt["dpdv"])
        si.dn_du, si.dn_dv = mi.Vector3f(*pt["dndu"]), mi.Vector3f(*pt["dndv"])
        si.duv_dx, si.duv_dy = mi.Vector2f(*pt["duvdx"]), mi.Vector2f(*pt["duvdy"])
        self.si = si

    def local(self, v):
        s, t, n = self.frame
        return mi.Vector3f(dot(v, s), dot(v, t), dot(v, n))

    def world(self, w):
        s, t, n = self.frame
        x, y, z = w[0], w[1], w[2]
        return (s[0] * x + t[0] * y + n[0] * z, s[1] * x + t[1] * y + n[1] * z, s[2] * x + t[2] * y + n[2] * z)

    def bsdf(self, m=None):
        m = m or self.state.material
        if isinstance(m, Missing):
            raise Unsupported(m.reason)
        key = (m, self.point_version if self.varies.get(m, True) else None)
        b = self.cache.get(key)
        if b is None:
            baker = materials.Baker(self.si)
            d = m.build(baker)
            b = mi.load_dict(d)
            self.varies[m] = baker.varies
            if len(self.cache) > 64:
                self.cache.clear()
            self.cache[(m, self.point_version if baker.varies else None)] = b
        return b

    def statement(self, text):
        return mitsuba_errors(self.apply, text)

    def query(self, word, args):
        return mitsuba_errors(self.answer, word, args)

    def apply(self, text):
        """Applies scene text; the materials it makes are built at once, at
        the current point, so that their errors are the statement's."""
        st = self.state
        st.made.clear()
        st.apply(text)
        for w in st.warnings:
            sys.stderr.write("warning %s\n" % w)
        st.warnings.clear()
        for m in st.made:
            self.bsdf(m)
        return "ok"

    def answer(self, word, args):
        if word == "eval":
            dirs = qp.eval_args(args)
            if dirs is None:
                return "0 0 0 0"
            wo, wi = dirs
            b = self.bsdf()
            si = self.si
            si.wi = self.local(wo)
            w = self.local(wi)
            value, pdf = b.eval_pdf(self.ctx, si, w)
            c = abs(w.z)
            if c == 0:
                return "0 0 0 %.9g" % pdf
            return "%.9g %.9g %.9g %.9g" % (value[0] / c, value[1] / c, value[2] / c, pdf)
        if word == "sample":
            a = qp.sample_args(args)
            return self.sample(self.bsdf(), *a) if a is not None else qp.FAILED_SAMPLE
        if word == "at":
            self.point = qp.at(self.point, args)
            self.point_version += 1
            self.set_frame()
            return "ok"
        if word == "conventions":
            return "transport %s sample-numbers 3" % self.transport
        if word == "version":
            return "protocol %d mitsuba3 %s precision float" % (qp.PROTOCOL, mi.__version__)
        if word == "mode":
            if len(args) != 1 or args[0] not in ("pbrt-v2", "corrected"):
                raise InputError("mode: pbrt-v2 or corrected")
            return "ok"  # Mitsuba has one behaviour: pbrt-v2's errata are not its business
        if word == "bssrdf":
            m = self.state.material
            if isinstance(m, Missing):
                raise Unsupported(m.reason)
            if m.bssrdf:
                raise Unsupported("bssrdf: Mitsuba 3 has no BSSRDF (its path tracers take participating media)")
            return "none"
        if word == "shading":
            pt = self.point
            return fmt(pt["n"] + pt["dpdu"] + pt["dpdv"])
        if word == "texture":
            return self.texture(args)
        if word == "rho":
            raise Unsupported("rho: Mitsuba 3's BSDFs have no albedo query")
        raise InputError("%s: takes no arguments" % word)

    def sample(self, b, wo, uc, u1, u2):
        si = self.si
        si.wi = self.local(wo)
        bs, weight = b.sample(self.ctx, si, uc, mi.Point2f(u1, u2))
        w = bs.wo
        pdf, t = bs.pdf, int(bs.sampled_type)
        c = abs(w.z)
        if not pdf > 0 or c == 0:
            return qp.FAILED_SAMPLE
        if weight[0] == 0 and weight[1] == 0 and weight[2] == 0:
            # Mitsuba zeroes the weight of an invalid sample (a microfacet seen
            # from behind, a reflection below the horizon) and keeps its
            # direction and pdf: failed, as Mitsuba's own chi2 test counts it
            return qp.FAILED_SAMPLE
        k = pdf / c
        wi = self.world(w)
        return "%.9g %.9g %.9g %.9g %.9g %.9g %.9g %d" % (wi[0], wi[1], wi[2], weight[0] * k, weight[1] * k,
                                                          weight[2] * k, pdf, pbrt_flags(t))

    def texture(self, args):
        if len(args) != 1 or len(args[0]) < 2 or args[0][0] != '"' or args[0][-1] != '"':
            raise InputError('texture: needs "NAME"')
        name = args[0][1:-1]
        st = self.state
        src = st.float_tex.get(name, st.color_tex.get(name))
        if src is None:
            raise InputError('texture: no texture named "%s"' % name)
        if isinstance(src, Missing):
            raise Unsupported(src.reason)
        baker = materials.Baker(self.si)
        return fmt([baker.float(src)] if src.kind == "float" else baker.color(src))


def main(argv):
    transport, directory, i = "radiance", os.getcwd(), 0
    while i < len(argv):
        val = argv[i + 1] if i + 1 < len(argv) else None
        if argv[i] == "--transport" and val in ("radiance", "importance"):
            transport = val
        elif argv[i] == "--microfacet" and val in ("beckmann", "ggx"):
            materials.MICROFACET[0] = val
        elif argv[i] == "--dir" and val is not None:
            directory = val
        else:
            sys.stderr.write("usage: materia_mitsuba.py [--transport radiance|importance] [--microfacet beckmann|ggx] "
                             "[--dir DIR]\n")
            return 2
        i += 2
    return qp.serve(Session(transport, directory))


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
