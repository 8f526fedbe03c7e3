#!/usr/bin/env python3
"""A small implementation of four of pbrt-v2's materials -- matte (Lambertian
or Oren-Nayar), plastic (Lambertian plus a Blinn microfacet lobe), mirror
(specular reflection) and glass (specular reflection and transmission) --
written from pbrt-v2's formulas (reflection.h/.cpp, montecarlo.cpp, matte.cpp,
plastic.cpp, mirror.cpp, glass.cpp), independent of materia, in double
precision. It speaks materia's query protocol (docs/PROTOCOL.md) on standard
input and output, so that materia-conformance --impl, materia-lobe --impl and
the conformance vectors can check it.

    python3 examples/pbrt_materials.py [--bug NAME] [--transport importance|radiance]
        [--sample-numbers 3|2] [--declare-transport T] [--declare-sample-numbers N]

--bug plants a deliberate error (see BUGS) to show what the checks report.
--transport and --sample-numbers choose the conventions it follows (the
`conventions` query declares them; docs/PROTOCOL.md):
  importance      pbrt-v2's specular transmission, weight (1 - F) T (default)
  radiance        pbrt-v3's radiance mode: that weight times (eta_i / eta_t)^2,
                  eta_i the index on wo's side
  3               pbrt-v2's BSDF::Sample_f: uc chooses the component, u1 and u2
                  its direction (default)
  2               pbrt-v3's: uc chooses, then uc * n - (its index) is the
                  component's first number, u1 its second; u2 is unused
--declare-transport and --declare-sample-numbers make it declare something
other than what it does: a lie the conformance suite must catch.
Only what these materials need is implemented: "Material" statements with
rgb/color/float parameters, the protocol's query lines; rho and texture are
answered with an error, bssrdf with none.
"""
import math
import os
import struct
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import query_protocol as qp  # noqa: E402 (the protocol's lines: examples/query_protocol.py)

INV_PI = 1 / math.pi

BUGS = {
    "pdf": "the Lambertian pdf 5% high",
    "fresnel": "plastic's Fresnel term from the wrong side in both modes",
    "colour": "the green channel of every f 3% low (a delta lobe's weight too)",
}
BUG = None

# its conventions: what it does, and what it declares (the same unless told)
TRANSPORT, SAMPLE_NUMBERS = "importance", 3
DECLARED = {}

REFLECTION, TRANSMISSION, DIFFUSE, GLOSSY, SPECULAR = 1, 2, 4, 8, 16


# ---- vectors -----------------------------------------------------------------
def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def normalize(a):
    l = math.sqrt(dot(a, a))
    return (a[0] / l, a[1] / l, a[2] / l)


def abs_cos(w):
    return abs(w[2])


def sin_theta(w):
    return math.sqrt(max(0.0, 1 - w[2] * w[2]))


def same_hemisphere(a, b):
    return a[2] * b[2] > 0


# ---- BxDFs (pbrt-v2 reflection.h/.cpp) ----------------------------------------
def concentric_sample_disk(u1, u2):
    sx, sy = 2 * u1 - 1, 2 * u2 - 1
    if sx == 0 and sy == 0:
        return 0.0, 0.0
    if sx >= -sy:
        if sx > sy:
            r = sx
            theta = sy / r if sy > 0 else 8 + sy / r
        else:
            r = sy
            theta = 2 - sx / r
    else:
        if sx <= sy:
            r = -sx
            theta = 4 - sy / r
        else:
            r = -sy
            theta = 6 + sx / r
    theta *= math.pi / 4
    return r * math.cos(theta), r * math.sin(theta)


class Diffuse:
    """BxDF's default sampling: the cosine-weighted hemisphere of wo."""
    type = REFLECTION | DIFFUSE

    def pdf(self, wo, wi):
        p = abs_cos(wi) * INV_PI if same_hemisphere(wo, wi) else 0.0
        return p * 1.05 if BUG == "pdf" else p

    def sample_f(self, wo, u1, u2):
        x, y = concentric_sample_disk(u1, u2)
        wi = (x, y, math.sqrt(max(0.0, 1 - x * x - y * y)))
        if wo[2] < 0:
            wi = (wi[0], wi[1], -wi[2])
        return wi, self.f(wo, wi), self.pdf(wo, wi)


class Lambertian(Diffuse):
    def __init__(self, r):
        self.r = r

    def f(self, wo, wi):
        return [c * INV_PI for c in self.r]


class OrenNayar(Diffuse):
    def __init__(self, r, sigma_deg):
        s2 = math.radians(sigma_deg) ** 2
        self.r, self.a, self.b = r, 1 - s2 / (2 * (s2 + 0.33)), 0.45 * s2 / (s2 + 0.09)

    def f(self, wo, wi):
        sti, sto = sin_theta(wi), sin_theta(wo)
        maxcos = 0.0
        if sti > 1e-4 and sto > 1e-4:
            def clamp(v):
                return max(-1.0, min(1.0, v))
            dcos = clamp(wi[0] / sti) * clamp(wo[0] / sto) + clamp(wi[1] / sti) * clamp(wo[1] / sto)
            maxcos = max(0.0, dcos)
        ci, co = abs_cos(wi), abs_cos(wo)
        if ci > co:
            sinalpha, tanbeta = sto, sti / ci
        elif co > 0:
            sinalpha, tanbeta = sti, sto / co
        else:
            return [c * INV_PI * self.a for c in self.r]
        return [c * INV_PI * (self.a + self.b * maxcos * sinalpha * tanbeta) for c in self.r]


def fresnel_dielectric(cosi, eta_i, eta_t):
    """pbrt-v2 FresnelDielectric::Evaluate."""
    cosi = max(-1.0, min(1.0, cosi))
    if cosi <= 0:
        eta_i, eta_t = eta_t, eta_i
    sint = eta_i / eta_t * math.sqrt(max(0.0, 1 - cosi * cosi))
    if sint >= 1:
        return 1.0
    cost = math.sqrt(max(0.0, 1 - sint * sint))
    cosi = abs(cosi)
    rparl = (eta_t * cosi - eta_i * cost) / (eta_t * cosi + eta_i * cost)
    rperp = (eta_i * cosi - eta_t * cost) / (eta_i * cosi + eta_t * cost)
    return (rparl * rparl + rperp * rperp) / 2


class BlinnMicrofacet:
    """Torrance-Sparrow with the Blinn distribution and a dielectric coat."""
    type = REFLECTION | GLOSSY

    def __init__(self, r, exponent, eta_i, eta_t, corrected):
        self.r, self.e = r, 10000.0 if exponent > 10000 or exponent != exponent else exponent
        self.eta_i, self.eta_t, self.corrected = eta_i, eta_t, corrected

    def f(self, wo, wi):
        co, ci = abs_cos(wo), abs_cos(wi)
        if co == 0 or ci == 0:
            return [0.0, 0.0, 0.0]
        wh = (wo[0] + wi[0], wo[1] + wi[1], wo[2] + wi[2])
        if wh == (0.0, 0.0, 0.0):
            return [0.0, 0.0, 0.0]
        wh = normalize(wh)
        cos_h = dot(wi, wh)
        # corrected mode turns wh to +z: a coat seen from below uses its
        # inside index (materia's erratum microfacet-fresnel-cosine)
        fcos = -cos_h if self.corrected and wh[2] < 0 else cos_h
        d = (self.e + 2) / (2 * math.pi) * abs_cos(wh) ** self.e
        ndotwh = abs_cos(wh)
        g = 1.0 if cos_h == 0 else min(1.0, 2 * ndotwh * co / abs(cos_h), 2 * ndotwh * ci / abs(cos_h))
        fr = fresnel_dielectric(fcos, self.eta_i, self.eta_t)
        return [c * d * g * fr / (4 * ci * co) for c in self.r]

    def pdf_h(self, costheta, wodotwh):
        if wodotwh <= 0:
            return 0.0
        return (self.e + 1) * costheta ** self.e / (2 * math.pi * 4 * wodotwh)

    def pdf(self, wo, wi):
        if not same_hemisphere(wo, wi):
            return 0.0
        wh = (wo[0] + wi[0], wo[1] + wi[1], wo[2] + wi[2])
        if wh == (0.0, 0.0, 0.0):
            return 0.0
        wh = normalize(wh)
        return self.pdf_h(abs_cos(wh), dot(wo, wh))

    def sample_f(self, wo, u1, u2):
        costheta = u1 ** (1 / (self.e + 1))
        sintheta = math.sqrt(max(0.0, 1 - costheta * costheta))
        phi = u2 * 2 * math.pi
        wh = (sintheta * math.cos(phi), sintheta * math.sin(phi), costheta)
        if not same_hemisphere(wo, wh):
            wh = (-wh[0], -wh[1], -wh[2])
        d = dot(wo, wh)
        wi = (-wo[0] + 2 * d * wh[0], -wo[1] + 2 * d * wh[1], -wo[2] + 2 * d * wh[2])
        pdf = self.pdf_h(costheta, d)
        if not same_hemisphere(wo, wi):
            # pbrt-v2 keeps the pdf (materia's erratum glossy-sample-pdf)
            return wi, [0.0, 0.0, 0.0], 0.0 if self.corrected else pdf
        return wi, self.f(wo, wi), pdf


class Delta:
    """A delta lobe: f and pdf are 0, only sample_f carries energy."""

    def f(self, wo, wi):
        return [0.0, 0.0, 0.0]

    def pdf(self, wo, wi):
        return 0.0


class SpecularReflection(Delta):
    """SpecularReflection with FresnelDielectric(eta_i, eta_t) (glass.cpp), or
    with FresnelNoOp when eta_i is None (mirror.cpp)."""
    type = REFLECTION | SPECULAR

    def __init__(self, r, eta_i=None, eta_t=None):
        self.r, self.eta_i, self.eta_t = r, eta_i, eta_t

    def sample_f(self, wo, u1, u2):
        wi = (-wo[0], -wo[1], wo[2])
        if wi[2] == 0:
            # pbrt-v2 divides by |cos theta| = 0 here; the sample fails, as in
            # materia (erratum grazing-division, fixed in both modes)
            return wi, [0.0, 0.0, 0.0], 0.0
        fr = 1.0 if self.eta_i is None else fresnel_dielectric(wo[2], self.eta_i, self.eta_t)
        return wi, [fr * c / abs_cos(wi) for c in self.r], 1.0


class SpecularTransmission(Delta):
    """pbrt-v2's SpecularTransmission (reflection.cpp): refraction by Snell's
    law, weight (1 - F) T; in the radiance convention times (eta_i/eta_t)^2,
    which pbrt-v2 leaves commented out (materia's erratum
    specular-transmission-eta2) and pbrt-v3 applies in radiance mode."""
    type = TRANSMISSION | SPECULAR

    def __init__(self, t, eta_i, eta_t):
        self.t, self.eta_i, self.eta_t = t, eta_i, eta_t

    def sample_f(self, wo, u1, u2):
        entering = wo[2] > 0
        ei, et = (self.eta_i, self.eta_t) if entering else (self.eta_t, self.eta_i)
        eta = ei / et
        sint2 = eta * eta * max(0.0, 1 - wo[2] * wo[2])
        if sint2 >= 1:  # total internal reflection: no sample
            return wo, [0.0, 0.0, 0.0], 0.0
        cost = math.sqrt(max(0.0, 1 - sint2))
        wi = (-eta * wo[0], -eta * wo[1], -cost if entering else cost)
        if wi[2] == 0:
            return wi, [0.0, 0.0, 0.0], 0.0
        w = 1 - fresnel_dielectric(wo[2], self.eta_i, self.eta_t)
        if TRANSPORT == "radiance":
            w *= (ei * ei) / (et * et)
        return wi, [w * c / abs_cos(wi) for c in self.t], 1.0


# ---- the BSDF (pbrt-v2 reflection.cpp BSDF) -------------------------------------
class BSDF:
    def __init__(self, n, ng, dpdu, bxdfs, corrected):
        nn = qp.admit(n)
        sn = dpdu
        if corrected:  # erratum bsdf-frame: dpdu made perpendicular to n
            d = dot(nn, sn)
            sn = (sn[0] - d * nn[0], sn[1] - d * nn[1], sn[2] - d * nn[2])
        self.s = normalize(sn)
        self.t = cross(nn, self.s)
        self.n, self.ng, self.bxdfs, self.corrected = nn, ng, bxdfs, corrected

    def to_local(self, v):
        return (dot(v, self.s), dot(v, self.t), dot(v, self.n))

    def to_world(self, v):
        s, t, n = self.s, self.t, self.n
        return tuple(s[i] * v[0] + t[i] * v[1] + n[i] * v[2] for i in range(3))

    def leak_flags(self, wo_w, wi_w):
        di, do = dot(wi_w, self.ng), dot(wo_w, self.ng)
        if self.corrected and (di == 0 or do == 0):  # erratum tangent-plane
            return 0
        return REFLECTION if di * do > 0 else TRANSMISSION

    def f_sum(self, wo, wi, side):
        total = [0.0, 0.0, 0.0]
        for b in self.bxdfs:
            if b.type & side:
                total = [a + c for a, c in zip(total, b.f(wo, wi))]
        if BUG == "colour":
            total[1] *= 0.97
        return total

    def f(self, wo_w, wi_w):
        side = self.leak_flags(wo_w, wi_w)
        if not side:
            return [0.0, 0.0, 0.0]
        return self.f_sum(self.to_local(wo_w), self.to_local(wi_w), side)

    def pdf(self, wo_w, wi_w):
        if not self.bxdfs:
            return 0.0
        wo, wi = self.to_local(wo_w), self.to_local(wi_w)
        return sum(b.pdf(wo, wi) for b in self.bxdfs) / len(self.bxdfs)

    def sample(self, wo_w, uc, u1, u2):
        n = len(self.bxdfs)
        if n == 0:
            return None
        which = min(int(uc * n), n - 1)
        b = self.bxdfs[which]
        wo = self.to_local(wo_w)
        if SAMPLE_NUMBERS == 2:
            # pbrt-v3's BSDF::Sample_f: uc, rescaled to [0, 1) within the chosen
            # component's stratum, is its first number; u2 is not used
            u1, u2 = min(uc * n - which, 1 - 2.0 ** -53), u1
        wi, f, pdf = b.sample_f(wo, u1, u2)
        if pdf == 0:
            return None
        wi_w = self.to_world(wi)
        if not b.type & SPECULAR:
            pdf += sum(o.pdf(wo, wi) for o in self.bxdfs if o is not b)
        if n > 1:
            pdf /= n
        if not b.type & SPECULAR:
            side = self.leak_flags(wo_w, wi_w)
            f = self.f_sum(wo, wi, side) if side else [0.0, 0.0, 0.0]
        elif BUG == "colour":
            f = [f[0], f[1] * 0.97, f[2]]
        return wi_w, f, pdf, b.type


# ---- materials (matte.cpp, plastic.cpp, mirror.cpp) ---------------------------
def f32(x):
    """x as a C float: the defaults are pbrt-v2's float constants (0.1f, 0.9f)."""
    return struct.unpack("f", struct.pack("f", x))[0]


DEFAULTS = {
    "matte": {"Kd": [0.5] * 3, "sigma": 0.0},
    "plastic": {"Kd": [0.25] * 3, "Ks": [0.25] * 3, "roughness": f32(0.1)},
    "mirror": {"Kr": [f32(0.9)] * 3},
    "glass": {"Kr": [1.0] * 3, "Kt": [1.0] * 3, "index": 1.5},
}


def make_bxdfs(kind, p, corrected):
    clamp = lambda c: [max(0.0, v) for v in c]  # Spectrum::Clamp
    if kind == "matte":
        kd, sigma = clamp(p["Kd"]), max(0.0, min(90.0, p["sigma"]))
        return [Lambertian(kd) if sigma == 0 else OrenNayar(kd, sigma)]
    if kind == "plastic":
        # both lobes whatever Kd and Ks are, as the reference pbrt-v2 binary
        # builds them (materia's src/materials/plastic.c)
        kd, ks = clamp(p["Kd"]), clamp(p["Ks"])
        # pbrt-v2 builds FresnelDielectric(1.5, 1); corrected (1, 1.5)
        eta_i, eta_t = (1.0, 1.5) if corrected else (1.5, 1.0)
        if BUG == "fresnel":
            eta_i, eta_t = eta_t, eta_i
        return [Lambertian(kd), BlinnMicrofacet(ks, 1 / p["roughness"], eta_i, eta_t, corrected)]
    if kind == "glass":
        # pbrt-v2 adds each lobe only when its colour is not black
        kr, kt, e = clamp(p["Kr"]), clamp(p["Kt"]), p["index"]
        return ([SpecularReflection(kr, 1.0, e)] if max(kr) > 0 else []) + \
            ([SpecularTransmission(kt, 1.0, e)] if max(kt) > 0 else [])
    return [SpecularReflection(clamp(p["Kr"]))]


# ---- statements ----------------------------------------------------------------
def tokens(text):
    out, i = [], 0
    while i < len(text):
        c = text[i]
        if c.isspace():
            i += 1
        elif c == "#":
            while i < len(text) and text[i] != "\n":
                i += 1
        elif c == '"':
            j = text.find('"', i + 1)
            if j < 0:
                raise ValueError("unclosed string")
            out.append(("s", text[i + 1:j]))
            i = j + 1
        elif c in "[]":
            out.append((c, c))
            i += 1
        else:
            j = i
            while j < len(text) and not text[j].isspace() and text[j] not in '[]"':
                j += 1
            out.append(("w", text[i:j]))
            i = j
    return out


def parse_material(text):
    t = tokens(text)
    materials = []
    i = 0
    while i < len(t):
        if t[i] != ("w", "Material"):
            raise ValueError("this example takes only Material statements, not %s" % t[i][1])
        if i + 1 >= len(t) or t[i + 1][0] != "s":
            raise ValueError("Material needs a quoted type")
        kind = t[i + 1][1]
        if kind not in DEFAULTS:
            raise ValueError('material type "%s" is not one of this example\'s (matte, plastic, mirror, glass)' % kind)
        params = dict(DEFAULTS[kind])
        i += 2
        while i < len(t) and t[i][0] == "s":
            decl = t[i][1].split()
            if len(decl) != 2:
                raise ValueError('parameter "%s": needs a type and a name' % t[i][1])
            ptype, name = decl
            i += 1
            values = []
            if i < len(t) and t[i][0] == "[":
                i += 1
                while i < len(t) and t[i][0] != "]":
                    values.append(t[i][1])
                    i += 1
                i += 1
            elif i < len(t):
                values.append(t[i][1])
                i += 1
            try:
                nums = [float(v) for v in values]
            except (ValueError, OverflowError):
                raise ValueError('parameter "%s": numbers wanted' % name)
            if name not in params:
                continue  # pbrt-v2 ignores (and warns about) unused parameters
            if ptype in ("rgb", "color"):
                if len(nums) != 3:
                    raise ValueError('parameter "%s": rgb takes three values' % name)
                params[name] = nums
            elif ptype == "float":
                if len(nums) != 1:
                    raise ValueError('parameter "%s": one value wanted' % name)
                params[name] = nums[0]
            else:
                raise ValueError('parameter "%s": type %s is not supported here' % (name, ptype))
        materials.append((kind, params))
    if not materials:
        raise ValueError("no statement")
    return materials[-1]


# ---- the session -------------------------------------------------------------------
class Session:
    def __init__(self):
        self.corrected = False
        self.material = ("matte", dict(DEFAULTS["matte"]))
        self.point = dict(qp.AT_DEFAULTS)

    def bsdf(self):
        kind, p = self.material
        pt = self.point
        return BSDF(pt["n"], pt["ng"], pt["dpdu"], make_bxdfs(kind, p, self.corrected), self.corrected)

    def statement(self, text):
        self.material = parse_material(text)
        return "ok"

    def query(self, word, args):
        if word == "version":
            if args:
                raise ValueError("version: takes no arguments")
            return "protocol %d pbrt_materials.py 0.1 precision double" % qp.PROTOCOL
        if word == "conventions":
            if args:
                raise ValueError("conventions: takes no arguments")
            return "transport %s sample-numbers %d" % (DECLARED.get("transport", TRANSPORT),
                                                        DECLARED.get("sample-numbers", SAMPLE_NUMBERS))
        if word == "mode":
            if len(args) != 1 or args[0] not in ("pbrt-v2", "corrected"):
                raise ValueError("mode: pbrt-v2 or corrected")
            self.corrected = args[0] == "corrected"
            return "ok"
        if word == "at":
            self.point = qp.at(self.point, args)
            return "ok"
        if word == "eval":
            dirs = qp.eval_args(args)
            if dirs is None:
                return "0 0 0 0"
            b = self.bsdf()
            return fmt(b.f(*dirs) + [b.pdf(*dirs)])
        if word == "sample":
            a = qp.sample_args(args)
            s = self.bsdf().sample(*a) if a is not None else None
            if s is None:
                return qp.FAILED_SAMPLE
            wi, f, pdf, flags = s
            return fmt(list(wi) + f + [pdf]) + " %d" % flags
        if word == "shading":
            pt = self.point
            return fmt(list(pt["n"]) + list(pt["dpdu"]) + list(pt["dpdv"]))
        if word == "bssrdf":
            return "none"
        raise ValueError("%s: not implemented by this example" % word)


def fmt(values):
    return " ".join("%.17g" % v for v in values)


USAGE = ("usage: pbrt_materials.py [--bug %s] [--transport importance|radiance] [--sample-numbers 3|2]\n"
         "       [--declare-transport importance|radiance] [--declare-sample-numbers 3|2]\n" % "|".join(BUGS))


def options(args):
    """Sets BUG and the conventions from the command line; False on a mistake."""
    global BUG, TRANSPORT, SAMPLE_NUMBERS
    choices = {"--bug": tuple(BUGS), "--transport": ("importance", "radiance"), "--sample-numbers": ("3", "2"),
               "--declare-transport": ("importance", "radiance"), "--declare-sample-numbers": ("3", "2")}
    seen = set()
    for i in range(0, len(args), 2):
        opt, val = args[i], args[i + 1] if i + 1 < len(args) else None
        if opt not in choices or val not in choices[opt] or opt in seen:
            return False
        seen.add(opt)
        if opt == "--bug":
            BUG = val
        elif opt == "--transport":
            TRANSPORT = val
        elif opt == "--sample-numbers":
            SAMPLE_NUMBERS = int(val)
        elif opt == "--declare-transport":
            DECLARED["transport"] = val
        else:
            DECLARED["sample-numbers"] = int(val)
    return True


def main():
    if not options(sys.argv[1:]):
        sys.stderr.write(USAGE)
        return 2
    return qp.serve(Session())


if __name__ == "__main__":
    sys.exit(main())
