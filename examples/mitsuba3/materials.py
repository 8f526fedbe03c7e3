"""pbrt-v2's materials and textures as Mitsuba 3 plugins (scalar_rgb variant).

Each material statement becomes a Material whose build() returns the
dictionary mi.load_dict() takes. What maps, with which conversion, and what is
`unsupported` (README.md in this directory has the same table):

  matte        twosided(diffuse: reflectance Kd); sigma > 0 (Oren-Nayar) unsupported
  plastic      twosided(roughplastic: beckmann, alpha from roughness, int_ior 1.5,
               diffuse_reflectance Kd, specular_reflectance Ks)
  glass        dielectric: int_ior index, specular_reflectance Kr, specular_transmittance Kt
  mirror       twosided(conductor: material "none" (a perfect mirror), specular_reflectance Kr)
  metal        twosided(roughconductor: beckmann, alpha from roughness, eta and k,
               or Mitsuba's "Cu" when neither is given)
  uber         without Kr and Kt: twosided(roughplastic: int_ior index, ...), inside
               mask(opacity) when opacity < 1; with Kr or Kt unsupported
  mix          blendbsdf: weight amount, bsdf_0 namedmaterial2, bsdf_1 namedmaterial1
  subsurface, kdsubsurface
               their BSDF, a Fresnel interface: dielectric with int_ior index,
               specular_reflectance Kr, specular_transmittance 0 (what enters is the
               BSSRDF's, which Mitsuba 3 does not have: `bssrdf` is unsupported)
  shinymetal, substrate, translucent, measured: unsupported
  "mitsuba:PLUGIN"
               any Mitsuba BSDF plugin by name, its parameters by Mitsuba's names
               (float, integer, bool, string, rgb, spectrum, texture; "string bsdf"
               and "string bsdf_0", "bsdf_1" name the named materials it nests),
               inside twosided unless it transmits or "bool twosided" "false" is given

A pbrt-v2 Blinn exponent e = 1/roughness (clamped to 10000, as pbrt-v2's Blinn
does) becomes the Beckmann alpha with the same second moment of the slopes,
alpha = sqrt(2 / (e + 2)) (Walter et al. 2007, "Microfacet models for refraction
through rough surfaces", section 5.2): roughness 0.1 -> 0.408, 0.01 -> 0.140,
0.001 -> 0.0447, 1 -> 0.816. With --microfacet ggx the same alpha is GGX's (its
slopes have no finite variance to match; pbrt-v3 too maps one roughness to
either distribution's alpha with one function).

Textures: constant, and checkerboard with dimension 2 and the uv mapping (Mitsuba's
checkerboard has period 1 in its uv and squares of 1/2; pbrt-v2's has squares of
1 in (s, t) = (uscale u + udelta, vscale v + vdelta), so to_uv halves (s, t)).
Every other texture class, bump maps and a 3D mapping are unsupported. Where a
Mitsuba plugin takes a number and pbrt-v2 a texture (roughness, index, amount,
opacity, sigma), the texture is evaluated by Mitsuba at the query's shading
point and the BSDF rebuilt when the point moves.
"""
import math

import mitsuba as mi

from pbrt_scene import InputError, Missing, Unsupported, spectrum_value


# ---- parameter values: constants, Mitsuba textures, and what cannot be had ---------
class Const:
    def __init__(self, kind, value):
        self.kind, self.value = kind, value  # kind "float" (a number) or "color" ([r, g, b])


class Tex:
    def __init__(self, kind, mdict, what):
        self.kind, self.mdict, self.what = kind, mdict, what
        self.loaded = None


def require(src):
    if isinstance(src, Missing):
        raise Unsupported(src.reason)
    return src


def color_param(ps, name, default, state):
    """pbrt-v2's GetSpectrumTexture: "texture NAME" first, then a value."""
    tname = ps.texture_name(name)
    if tname is not None:
        if tname not in state.color_tex:
            raise InputError('parameter "%s": no color texture named "%s"' % (name, tname))
        return require(state.color_tex[tname])
    p = ps.get(name, ("rgb", "color", "xyz", "spectrum", "blackbody"))
    if p is None:
        return Const("color", [default] * 3)
    kind, v = spectrum_value(p, state.resolve)
    return Const("color", v) if kind == "rgb" else Tex("color", v, 'parameter "%s"' % name)


def float_param(ps, name, default, state):
    """pbrt-v2's GetFloatTexture: "texture NAME" first, then a value."""
    tname = ps.texture_name(name)
    if tname is not None:
        if tname not in state.float_tex:
            raise InputError('parameter "%s": no float texture named "%s"' % (name, tname))
        return require(state.float_tex[tname])
    return Const("float", ps.float(name, default))


def no_bump(ps, state, kind):
    tname = ps.texture_name("bumpmap")
    if tname is None:
        return
    if tname in state.float_tex:
        require(state.float_tex[tname])
    raise Unsupported("%s with a bump map: Mitsuba's bumpmap differentiates a bitmap in uv, pbrt-v2's Bump() "
                      "any float texture over the surface; not mapped" % kind)


def clone(d):
    """A copy of a plugin dictionary's dicts and lists (the objects in it, a
    transform, are shared: mi.load_dict only reads them)."""
    if isinstance(d, dict):
        return {k: clone(v) for k, v in d.items()}
    if isinstance(d, list):
        return [clone(v) for v in d]
    return d


def to_mitsuba(src, bounded=True):
    """A constant or texture as a Mitsuba texture property."""
    if isinstance(src, Tex):
        return clone(src.mdict)
    if src.kind == "float":
        return float(src.value)
    v = [max(0.0, float(x)) for x in src.value]  # pbrt-v2's Spectrum::Clamp()
    if bounded and max(v) > 1:
        raise Unsupported("the colour %s: Mitsuba's rgb reflectances are in [0, 1]" % v)
    return {"type": "rgb", "value": v}


class Baker:
    """Evaluates parameters at the shading point, through Mitsuba's textures;
    remembers whether any value came from a texture (then the BSDF depends on
    the point)."""

    def __init__(self, si):
        self.si, self.varies = si, False

    def texture(self, t):
        if t.loaded is None:
            t.loaded = mi.load_dict(t.mdict)
        self.varies = True
        return t.loaded

    def float(self, src):
        if isinstance(src, Const):
            return float(src.value)
        return float(self.texture(src).eval_1(self.si))

    def color(self, src):
        if isinstance(src, Const):
            return [float(x) for x in src.value]
        v = self.texture(src).eval(self.si)
        return [float(v[0]), float(v[1]), float(v[2])]

    def grey(self, src, what):
        """A colour parameter where Mitsuba takes one number."""
        v = [max(0.0, x) for x in self.color(src)]
        if max(v) - min(v) > 1e-6 * max(v):
            raise Unsupported("%s %s: Mitsuba takes one number here, pbrt-v2's value differs between channels" %
                              (what, v))
        return v[0]


# The microfacet distribution pbrt-v2's Blinn lobes become: "beckmann" (the
# default, Blinn's closest relative) or "ggx" (materia_mitsuba.py --microfacet).
MICROFACET = ["beckmann"]


def alpha_of(roughness):
    """The Beckmann alpha of pbrt-v2's Blinn exponent 1/roughness."""
    if not roughness >= 0:
        raise InputError("roughness %g: must be >= 0 (the Blinn exponent 1/roughness)" % roughness)
    e = 1 / roughness if roughness > 0 else math.inf
    e = min(e, 10000.0)  # pbrt-v2's Blinn: exponents above 10000 are 10000
    return math.sqrt(2 / (e + 2))


def twosided(d):
    return {"type": "twosided", "bsdf": d}


# ---- materials -------------------------------------------------------------------
class Material:
    def __init__(self, kind, build, bssrdf=False):
        self.kind, self.build_fn, self.bssrdf = kind, build, bssrdf

    def build(self, baker):
        return self.build_fn(baker)


UNSUPPORTED = {
    "shinymetal": "shinymetal: pbrt-v2's conductor approximated from Ks and Kr, with a mirror lobe added, has no "
                  "Mitsuba 3 counterpart",
    "substrate": "substrate: pbrt-v2's FresnelBlend (Ashikhmin-Shirley, anisotropic) has no Mitsuba 3 counterpart "
                 "(its coated diffuse is roughplastic: Material \"mitsuba:roughplastic\")",
    "translucent": "translucent: Mitsuba 3 has no diffuse or glossy transmission through a thin sheet",
    "measured": "measured: Mitsuba 3's measured BSDF reads the RGL database's tabulated files, not MERL tables",
}


def make_material(kind, ps, state):
    if kind in UNSUPPORTED:
        raise Unsupported(UNSUPPORTED[kind])
    if kind.startswith("mitsuba:"):
        return passthrough(kind[len("mitsuba:"):], ps, state)
    maker = MAKERS.get(kind)
    if maker is None:
        raise InputError('unknown material type "%s"' % kind)
    no_bump(ps, state, kind)
    return maker(ps, state)


def matte(ps, state):
    kd, sigma = color_param(ps, "Kd", 0.5, state), float_param(ps, "sigma", 0.0, state)

    def lambertian(s):
        if s != 0:
            raise Unsupported("matte with sigma %g: Oren-Nayar; Mitsuba 3 has no Oren-Nayar BSDF" % s)

    if isinstance(sigma, Const):
        lambertian(sigma.value)

    def build(b):
        lambertian(b.float(sigma))
        return twosided({"type": "diffuse", "reflectance": to_mitsuba(kd)})

    return Material("matte", build)


def coat(b, kd, ks, rough, index):
    """pbrt-v2's Lambertian + Blinn microfacet under a dielectric Fresnel term,
    as Mitsuba's rough plastic (a diffuse base under a rough dielectric coat)."""
    return twosided({"type": "roughplastic", "distribution": MICROFACET[0], "alpha": alpha_of(b.float(rough)),
                     "int_ior": index, "ext_ior": 1.0, "diffuse_reflectance": to_mitsuba(kd),
                     "specular_reflectance": to_mitsuba(ks)})


def plastic(ps, state):
    kd, ks = color_param(ps, "Kd", 0.25, state), color_param(ps, "Ks", 0.25, state)
    rough = float_param(ps, "roughness", 0.1, state)
    return Material("plastic", lambda b: coat(b, kd, ks, rough, 1.5))


def index_of(b, src):
    e = b.float(src)
    if not e > 0:
        raise InputError("index %g: must be > 0" % e)
    return e


def glass(ps, state):
    kr, kt = color_param(ps, "Kr", 1.0, state), color_param(ps, "Kt", 1.0, state)
    index = float_param(ps, "index", 1.5, state)
    return Material("glass", lambda b: {"type": "dielectric", "int_ior": index_of(b, index), "ext_ior": 1.0,
                                        "specular_reflectance": to_mitsuba(kr),
                                        "specular_transmittance": to_mitsuba(kt)})


def mirror(ps, state):
    kr = color_param(ps, "Kr", 0.9, state)
    return Material("mirror", lambda b: twosided({"type": "conductor", "material": "none",
                                                  "specular_reflectance": to_mitsuba(kr)}))


COPPER = []


def mitsuba_copper():
    """Mitsuba's own copper (its "Cu" data in RGB), for a metal given only one
    of eta and k."""
    if not COPPER:
        p = mi.traverse(mi.load_dict({"type": "conductor", "material": "Cu"}))
        COPPER.extend([list(p["eta.value"]), list(p["k.value"])])
    return COPPER


def metal(ps, state):
    given = ps.texture_name("eta") is not None or ps.get("eta", ("rgb", "color", "xyz", "spectrum")) is not None, \
        ps.texture_name("k") is not None or ps.get("k", ("rgb", "color", "xyz", "spectrum")) is not None
    eta = color_param(ps, "eta", 0.0, state) if given[0] else None
    k = color_param(ps, "k", 0.0, state) if given[1] else None
    rough = float_param(ps, "roughness", 0.01, state)

    def build(b):
        d = {"type": "roughconductor", "distribution": MICROFACET[0], "alpha": alpha_of(b.float(rough))}
        if eta is None and k is None:
            d["material"] = "Cu"
        else:
            cu = mitsuba_copper()
            d["eta"] = to_mitsuba(eta, False) if eta else {"type": "rgb", "value": cu[0]}
            d["k"] = to_mitsuba(k, False) if k else {"type": "rgb", "value": cu[1]}
        return twosided(d)

    return Material("metal", build)


def uber(ps, state):
    kd, ks = color_param(ps, "Kd", 0.25, state), color_param(ps, "Ks", 0.25, state)
    kr, kt = color_param(ps, "Kr", 0.0, state), color_param(ps, "Kt", 0.0, state)
    rough, index = float_param(ps, "roughness", 0.1, state), float_param(ps, "index", 1.5, state)
    opacity = color_param(ps, "opacity", 1.0, state)

    def build(b):
        if max(b.color(kr)) > 0 or max(b.color(kt)) > 0:
            raise Unsupported("uber with Kr or Kt: no Mitsuba 3 BSDF adds specular lobes to a rough coat")
        d = coat(b, kd, ks, rough, index_of(b, index))
        op = b.grey(opacity, "uber opacity")
        if op > 1:
            raise Unsupported("uber opacity %g: above 1" % op)
        return d if op == 1 else {"type": "mask", "opacity": op, "bsdf": d}

    return Material("uber", build)


def mix(ps, state):
    names = [ps.string("namedmaterial1", None), ps.string("namedmaterial2", None)]
    mats = []
    for i, n in enumerate(names):
        if n is None:
            raise InputError('mix: "string namedmaterial%d" is missing' % (i + 1))
        if n not in state.named:
            raise InputError('mix: named material "%s" is not defined' % n)
        mats.append(require(state.named[n]))
    amount = color_param(ps, "amount", 0.5, state)

    def build(b):
        w = min(1.0, b.grey(amount, "mix amount"))
        # pbrt-v2: amount * m1 + (1 - amount) * m2; blendbsdf: (1 - weight) bsdf_0 + weight bsdf_1
        return {"type": "blendbsdf", "weight": w, "bsdf_0": mats[1].build(b), "bsdf_1": mats[0].build(b)}

    return Material("mix", build)


def interface(kind, index_default):
    def make(ps, state):
        kr, index = color_param(ps, "Kr", 1.0, state), float_param(ps, "index", index_default, state)
        for p in ps.by_name.values():  # the BSSRDF's parameters: not the BSDF's business
            p.used = True
        return Material(kind, lambda b: {"type": "dielectric", "int_ior": index_of(b, index), "ext_ior": 1.0,
                                         "specular_reflectance": to_mitsuba(kr),
                                         "specular_transmittance": 0.0}, bssrdf=True)
    return make


MAKERS = {"matte": matte, "plastic": plastic, "glass": glass, "mirror": mirror, "metal": metal, "uber": uber,
          "mix": mix, "subsurface": interface("subsurface", 1.3), "kdsubsurface": interface("kdsubsurface", 1.3)}


def passthrough(plugin, ps, state):
    """Material "mitsuba:PLUGIN": Mitsuba's parameters under their own names; a
    string parameter named bsdf, bsdf_0, bsdf_1 names a named material, the
    plugin's nested BSDF (mask, blendbsdf, twosided)."""
    props, nested, sided = {}, {}, True
    for p in ps.by_name.values():
        p.used = True
        if p.name == "twosided" and p.type == "bool":
            sided = p.values[0]
            continue
        if p.type == "string" and p.name.startswith("bsdf"):
            if p.values[0] not in state.named:
                raise InputError('parameter "%s": no named material "%s"' % (p.name, p.values[0]))
            nested[p.name] = require(state.named[p.values[0]])
            continue
        if p.type == "texture":
            src = state.color_tex.get(p.values[0], state.float_tex.get(p.values[0]))
            if src is None:
                raise InputError('parameter "%s": no texture named "%s"' % (p.name, p.values[0]))
            props[p.name] = to_mitsuba(require(src))
        elif p.type in ("rgb", "color", "xyz", "spectrum", "blackbody"):
            kind, v = spectrum_value(p, state.resolve)
            props[p.name] = {"type": "rgb", "value": v} if kind == "rgb" else v
        elif len(p.values) != 1:
            raise InputError('parameter "%s": one value wanted' % p.name)
        elif p.type == "integer":
            props[p.name] = int(p.values[0])
        else:
            props[p.name] = p.values[0]
    props["type"] = plugin

    def build(b):
        d = clone(props)
        for k, m in nested.items():
            d[k] = m.build(b)
        if sided:
            try:
                flags = mi.load_dict(d).flags()
            except RuntimeError as e:
                raise InputError("Mitsuba: %s" % str(e).replace("\n", " "))
            if not flags & int(mi.BSDFFlags.Transmission):
                d = twosided(d)
        return d

    return Material("mitsuba:" + plugin, build)


# ---- textures --------------------------------------------------------------------
def make_texture(tclass, kind, ps, state):
    if tclass == "constant":
        return color_param(ps, "value", 1.0, state) if kind == "color" else float_param(ps, "value", 1.0, state)
    if tclass != "checkerboard":
        raise Unsupported('Texture class "%s": not mapped to a Mitsuba 3 texture (only constant and a 2D '
                          'checkerboard are)' % tclass)
    dim, mapping = ps.integer("dimension", 2), ps.string("mapping", "uv")
    if dim != 2:
        raise Unsupported("a %dD checkerboard: Mitsuba 3's checkerboard is 2D" % dim)
    if mapping != "uv":
        raise Unsupported('checkerboard with the "%s" mapping: Mitsuba 3 maps textures by (u, v)' % mapping)
    su, sv = ps.float("uscale", 1.0), ps.float("vscale", 1.0)
    du, dv = ps.float("udelta", 0.0), ps.float("vdelta", 0.0)
    ps.string("aamode", "closedform")  # pbrt-v2 filters over the differentials; Mitsuba never does
    param = color_param if kind == "color" else float_param
    t1, t2 = param(ps, "tex1", 1.0, state), param(ps, "tex2", 0.0, state)
    T = mi.ScalarTransform3f
    # pbrt-v2: tex1 where floor(s) + floor(t) is even; Mitsuba: color0 where
    # frac(u') > 1/2 and frac(v') > 1/2 agree, so (u', v') = (s, t) / 2
    to_uv = T().scale([0.5, 0.5]) @ T().translate([du, dv]) @ T().scale([su, sv])
    return Tex(kind, {"type": "checkerboard", "color0": to_mitsuba(t1), "color1": to_mitsuba(t2), "to_uv": to_uv},
               "checkerboard")
