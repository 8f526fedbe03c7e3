"""pbrt-v2 scene text, as far as a material needs it: the tokenizer, parameter
lists, and the graphics state the query protocol keeps (textures, named
materials, the current material, AttributeBegin/AttributeEnd).

The rules are pbrt-v2's (core/parser.cpp, core/api.cpp, core/paramset.cpp):
a parameter is "type name" followed by one value or a bracketed list; a
material's spectrum parameter is looked up as a texture first ("texture Kd"),
then as a value (rgb, color, xyz, spectrum); Material, MakeNamedMaterial and
NamedMaterial select the material a shape would get; AttributeBegin saves the
material, the named materials and the textures, AttributeEnd restores them.
What to do with a material is materials.py's business; this file knows only
the statements.
"""


from query_protocol import Unsupported  # noqa: F401 (re-exported: what Mitsuba 3 lacks)


class InputError(ValueError):
    """Bad input: answered `error MESSAGE`."""


class Missing:
    """An unsupported texture or material, kept under its name: what uses it
    is unsupported for the same reason."""

    def __init__(self, reason):
        self.reason = reason


# ---- tokens ----------------------------------------------------------------------
def tokenize(text):
    """(kind, value, line) triples: kind 's' a quoted string, 'n' a number, 'w'
    a bare word, '[' and ']'. Comments run from # to the end of the line."""
    out, i, line, n = [], 0, 1, len(text)
    while i < n:
        c = text[i]
        if c == "\n":
            line += 1
            i += 1
        elif c.isspace():
            i += 1
        elif c == "#":
            while i < n and text[i] != "\n":
                i += 1
        elif c == '"':
            j = text.find('"', i + 1)
            if j < 0:
                raise InputError("line %d: unclosed string" % line)
            out.append(("s", text[i + 1:j], line))
            line += text.count("\n", i, j)
            i = j + 1
        elif c in "[]":
            out.append((c, c, line))
            i += 1
        else:
            j = i
            while j < n and not text[j].isspace() and text[j] not in '[]"#':
                j += 1
            word = text[i:j]
            try:
                out.append(("n", float(word), line))
            except ValueError:
                out.append(("w", word, line))
            i = j
    return out


# ---- parameter lists -------------------------------------------------------------
SPECTRUM_TYPES = ("rgb", "color", "xyz", "spectrum", "blackbody")
NUMERIC_TYPES = ("float", "integer", "point", "vector", "normal") + SPECTRUM_TYPES
KNOWN_TYPES = NUMERIC_TYPES + ("string", "texture", "bool")

# pbrt-v2's XYZToRGB (core/spectrum.h)
XYZ_TO_RGB = ((3.240479, -1.537150, -0.498535), (-0.969256, 1.875991, 0.041556),
              (0.055648, -0.204043, 1.057311))


class Param:
    __slots__ = ("type", "name", "values", "line", "used")

    def __init__(self, ptype, name, values, line):
        self.type, self.name, self.values, self.line, self.used = ptype, name, values, line, False


class ParamSet:
    """A statement's parameters by name; a later one of the same name wins, as
    in pbrt-v2's ParamSet."""

    def __init__(self, params):
        self.by_name = {}
        for p in params:
            self.by_name[p.name] = p

    def get(self, name, types):
        p = self.by_name.get(name)
        if p is None or p.type not in types:
            return None
        p.used = True
        return p

    def float(self, name, default):
        p = self.get(name, ("float",))
        if p is None:
            return default
        if len(p.values) != 1:
            raise InputError('parameter "%s": one value wanted, %d given' % (name, len(p.values)))
        return p.values[0]

    def string(self, name, default):
        p = self.get(name, ("string",))
        if p is None:
            return default
        if len(p.values) != 1:
            raise InputError('parameter "%s": one string wanted' % name)
        return p.values[0]

    def integer(self, name, default):
        p = self.get(name, ("integer",))
        if p is None:
            return default
        if len(p.values) != 1 or p.values[0] != int(p.values[0]):
            raise InputError('parameter "%s": one integer wanted' % name)
        return int(p.values[0])

    def texture_name(self, name):
        p = self.get(name, ("texture",))
        if p is None:
            return None
        if len(p.values) != 1:
            raise InputError('parameter "%s": one texture name wanted' % name)
        return p.values[0]

    def unused(self):
        return [p for p in self.by_name.values() if not p.used]


def spectrum_value(p, resolve):
    """A spectrum parameter's value as ('rgb', [r, g, b]) or ('spectrum', dict
    for Mitsuba's "spectrum" plugin). resolve turns a relative file name into
    a path."""
    v = p.values
    if p.type in ("rgb", "color"):
        if len(v) != 3:
            raise InputError('parameter "%s": %s takes three values, %d given' % (p.name, p.type, len(v)))
        return ("rgb", [float(x) for x in v])
    if p.type == "xyz":
        if len(v) != 3:
            raise InputError('parameter "%s": xyz takes three values, %d given' % (p.name, len(v)))
        return ("rgb", [sum(m[j] * v[j] for j in range(3)) for m in XYZ_TO_RGB])
    if p.type == "spectrum":
        if len(v) == 1 and isinstance(v[0], str):
            return ("spectrum", {"type": "spectrum", "filename": resolve(v[0])})
        if len(v) < 4 or len(v) % 2 or any(isinstance(x, str) for x in v):
            raise InputError('parameter "%s": spectrum takes a file name or wavelength-value pairs' % p.name)
        return ("spectrum", {"type": "spectrum", "value": [(v[i], v[i + 1]) for i in range(0, len(v), 2)]})
    raise Unsupported('parameter "%s": blackbody spectra are not mapped to Mitsuba' % p.name)


def parse_params(toks, i, directive):
    """The parameter list from toks[i]: (ParamSet, next index)."""
    params = []
    while i < len(toks) and toks[i][0] == "s":
        decl, line = toks[i][1].split(), toks[i][2]
        if len(decl) != 2:
            raise InputError('line %d: %s: parameter "%s" needs a type and a name' % (line, directive, toks[i][1]))
        ptype, name = decl
        if ptype == "point3":
            ptype = "point"
        if ptype not in KNOWN_TYPES:
            raise InputError('line %d: %s: parameter "%s": unknown type "%s"' % (line, directive, name, ptype))
        i += 1
        values = []
        if i < len(toks) and toks[i][0] == "[":
            i += 1
            while i < len(toks) and toks[i][0] != "]":
                if toks[i][0] not in ("s", "n", "w"):
                    raise InputError("line %d: %s: unexpected %s" % (toks[i][2], directive, toks[i][1]))
                values.append(toks[i][1])
                i += 1
            if i >= len(toks):
                raise InputError("line %d: %s: unclosed [" % (line, directive))
            i += 1
        elif i < len(toks) and toks[i][0] in ("s", "n"):
            values.append(toks[i][1])
            i += 1
        else:
            raise InputError('line %d: %s: parameter "%s" has no value' % (line, directive, name))
        if ptype in NUMERIC_TYPES and ptype != "spectrum" and not all(isinstance(x, float) for x in values):
            raise InputError('line %d: %s: parameter "%s": numbers wanted' % (line, directive, name))
        if ptype in ("string", "texture") and not all(isinstance(x, str) for x in values):
            raise InputError('line %d: %s: parameter "%s": quoted strings wanted' % (line, directive, name))
        if ptype == "bool":
            if not all(x in ("true", "false") for x in values):
                raise InputError('line %d: %s: parameter "%s": "true" or "false" wanted' % (line, directive, name))
            values = [x == "true" for x in values]
        params.append(Param(ptype, name, values, line))
    return ParamSet(params), i


# ---- the graphics state ------------------------------------------------------------
# The directives that change only the transform. No mapped texture reads the
# transform (Mitsuba's checkerboard maps (u, v), and pbrt-v2's 3D textures have
# no Mitsuba counterpart), so they are checked and have no effect.
TRANSFORM_ARGS = {"Identity": 0, "Translate": 3, "Scale": 3, "Rotate": 4, "LookAt": 9, "Transform": 16,
                  "ConcatTransform": 16, "ReverseOrientation": 0}
NAME_ARGS = ("CoordinateSystem", "CoordSysTransform", "ActiveTransform")


class State:
    """What the statements have set: textures (float and colour apart, as in
    pbrt-v2), named materials and the current material, each material as the
    object materials.make returns."""

    def __init__(self, make_material, make_texture, resolve):
        self.make_material, self.make_texture, self.resolve = make_material, make_texture, resolve
        self.float_tex, self.color_tex, self.named = {}, {}, {}
        self.material = make_material("matte", ParamSet([]), self)  # api.cpp's default
        self.stack, self.tstack = [], 0
        self.warnings = []
        self.made = []  # the materials the last statements made

    def apply(self, text):
        """Applies the statements of text (one or more). Raises InputError or
        Unsupported at the first that fails; those before it stay applied."""
        toks = tokenize(text)
        i = 0
        while i < len(toks):
            kind, word, line = toks[i]
            if kind != "w":
                raise InputError("line %d: a directive wanted, not %r" % (line, word))
            i = self.directive(word, toks, i + 1, line)

    @staticmethod
    def kept(table, key, make):
        """table[key] = make(); when that is unsupported, a Missing in its place
        before the error goes on (pbrt-v2 records the statement whatever it
        holds, and what uses it fails the same way)."""
        try:
            table[key] = make()
        except Unsupported as e:
            table[key] = Missing(str(e))
            raise

    def strings(self, toks, i, n, directive, line):
        vals = []
        for _ in range(n):
            if i >= len(toks) or toks[i][0] != "s":
                raise InputError("line %d: %s needs %d quoted string%s" % (line, directive, n, "s" if n > 1 else ""))
            vals.append(toks[i][1])
            i += 1
        return vals, i

    def warn_unused(self, ps, what):
        for p in ps.unused():
            self.warnings.append('%s: parameter "%s %s" is not used' % (what, p.type, p.name))

    def directive(self, word, toks, i, line):
        if word == "Material":
            (kind,), i = self.strings(toks, i, 1, word, line)
            ps, i = parse_params(toks, i, word)
            self.kept(self.__dict__, "material", lambda: self.make_material(kind, ps, self))
            self.made.append(self.material)
            self.warn_unused(ps, 'Material "%s"' % kind)
        elif word == "MakeNamedMaterial":
            (name,), i = self.strings(toks, i, 1, word, line)
            ps, i = parse_params(toks, i, word)
            kind = ps.string("type", None)
            if kind is None:
                raise InputError('line %d: MakeNamedMaterial "%s": no "string type"' % (line, name))
            self.kept(self.named, name, lambda: self.make_material(kind, ps, self))
            self.made.append(self.named[name])
            self.warn_unused(ps, 'MakeNamedMaterial "%s"' % name)
        elif word == "NamedMaterial":
            (name,), i = self.strings(toks, i, 1, word, line)
            if name not in self.named:
                raise InputError('line %d: NamedMaterial "%s" is not defined' % (line, name))
            self.material = self.named[name]
        elif word == "Texture":
            (name, ttype, tclass), i = self.strings(toks, i, 3, word, line)
            ps, i = parse_params(toks, i, word)
            if ttype not in ("float", "color", "spectrum"):
                raise InputError('line %d: Texture "%s": type "%s" is neither float nor color' % (line, name, ttype))
            kind = "float" if ttype == "float" else "color"
            table = self.float_tex if kind == "float" else self.color_tex
            self.kept(table, name, lambda: self.make_texture(tclass, kind, ps, self))
            self.warn_unused(ps, 'Texture "%s"' % name)
        elif word == "AttributeBegin":
            self.stack.append((self.material, dict(self.named), dict(self.float_tex), dict(self.color_tex),
                               self.tstack))
            self.tstack = 0
        elif word == "AttributeEnd":
            if not self.stack:
                raise InputError("line %d: AttributeEnd without AttributeBegin" % line)
            if self.tstack:
                raise InputError("line %d: AttributeEnd inside a TransformBegin" % line)
            self.material, self.named, self.float_tex, self.color_tex, self.tstack = self.stack.pop()
        elif word == "TransformBegin":
            self.tstack += 1
        elif word == "TransformEnd":
            if not self.tstack:
                raise InputError("line %d: TransformEnd without TransformBegin" % line)
            self.tstack -= 1
        elif word in TRANSFORM_ARGS:
            n, nums = TRANSFORM_ARGS[word], []
            if n == 16 and i < len(toks) and toks[i][0] == "[":
                j = i + 1
                while j < len(toks) and toks[j][0] == "n":
                    nums.append(toks[j][1])
                    j += 1
                if j >= len(toks) or toks[j][0] != "]":
                    raise InputError("line %d: %s: 16 numbers in brackets wanted" % (line, word))
                i = j + 1
            else:
                while len(nums) < n and i < len(toks) and toks[i][0] == "n":
                    nums.append(toks[i][1])
                    i += 1
            if len(nums) != n:
                raise InputError("line %d: %s takes %d numbers" % (line, word, n))
        elif word in NAME_ARGS:
            if i < len(toks) and toks[i][0] in ("s", "w"):
                i += 1
            else:
                raise InputError("line %d: %s needs a name" % (line, word))
        elif word == "AreaLightSource":
            (_kind,), i = self.strings(toks, i, 1, word, line)
            _ps, i = parse_params(toks, i, word)
        elif word == "Include":
            (name,), i = self.strings(toks, i, 1, word, line)
            try:
                with open(self.resolve(name)) as f:
                    text = f.read()
            except OSError as e:
                raise InputError('line %d: Include "%s": %s' % (line, name, e.strerror))
            self.apply(text)
        else:
            raise InputError("line %d: %s is not a statement this adapter takes" % (line, word))
        return i
