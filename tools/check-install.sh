#!/bin/sh
# make check's installation test: make install into a temporary DESTDIR, the
# files where they belong (a double build under its own names), a C program
# built against the installed library through pkg-config (shared and
# static) and run, then make uninstall leaving nothing behind. Prints
# PASS/FAIL lines for tools/run-checks.sh.
# usage: check-install.sh BUILD_DIR PRECISION   (MAKE and CC from the environment)
build=$1; precision=$2
make=${MAKE:-make}; cc=${CC:-cc}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/materia-install.XXXXXX") || exit 1
trap 'rm -rf "$tmp"' EXIT INT TERM
root=$tmp/root; prefix=/opt/materia
name=materia; suffix=
if [ "$precision" = double ]; then name=materia-double; suffix=-double; fi
status=0
pass() { echo "PASS install: $1"; }
fail() { echo "FAIL install: $1"; status=1; }

if $make --no-print-directory install DESTDIR="$root" PREFIX=$prefix BUILD="$build" PRECISION="$precision" \
    >"$tmp/log" 2>&1; then
    pass "make install DESTDIR=... PREFIX=$prefix"
else
    fail "make install failed:"; cat "$tmp/log"; exit 1
fi

inc=$root$prefix/include; [ "$precision" = double ] && inc=$inc/materia-double
missing=
for f in "$inc/materia.h" "$inc/materia/config.h" "$inc/materia/bsdf.h" \
         "$root$prefix/lib/lib$name.a" "$root$prefix/lib/lib$name.so.0" "$root$prefix/lib/lib$name.so" \
         "$root$prefix/lib/pkgconfig/$name.pc" "$root$prefix/lib/pkgconfig/$name-shared.pc" \
         "$root$prefix/share/doc/$name/LICENSE" \
         "$root$prefix/share/doc/$name/README.md" "$root$prefix/share/doc/$name/conformance/ERRATA.md" \
         "$root$prefix/bin/materia-render$suffix" "$root$prefix/bin/materia-query$suffix" \
         "$root$prefix/bin/materia-conformance$suffix"; do
    [ -e "$f" ] || missing="$missing ${f#$root}"
done
if [ -z "$missing" ]; then pass "headers, lib$name.a/.so, $name.pc, the tools$suffix, docs and LICENSE installed"
else fail "not installed:$missing"; fi
# what the installed documentation cites is installed: every relative link
# of its Markdown files (docs, vectors, examples, images) resolves there
doc=$root$prefix/share/doc/$name
broken=
for md in $(cd "$doc" && find . -name '*.md' | sort); do
    for target in $(grep -o '](\([^)#]*\)' "$doc/$md" | sed 's/^](//' | grep -v '^[a-z]*:' | sort -u); do
        [ -e "$(dirname "$doc/$md")/$target" ] || broken="$broken ${md#./}->$target"
    done
done
if [ -z "$broken" ] && [ -f "$doc/vectors/check.py" ] && [ -f "$doc/examples/README.md" ] &&
   [ -f "$doc/docs/CONFORMANCE-SUITE.md" ]; then
    pass "the installed docs' links resolve (vectors, check.py, the examples included)"
else
    fail "installed docs cite what is not installed:${broken:- vectors/check.py, examples/README.md or docs/}"
fi
# the installed check.py against the installed materia-query (a usage error
# for a lookahead: --only is a POSIX extended regular expression)
if command -v python3 >/dev/null 2>&1 && python3 -c 'import sys; sys.exit(sys.version_info < (3, 6))' 2>/dev/null; then
    if python3 "$doc/vectors/check.py" --impl "$root$prefix/bin/materia-query$suffix" --precision "$precision" \
           --only '^matte default$' >"$tmp/log" 2>&1 && grep -q '^PASS' "$tmp/log" && ! grep -q '^FAIL' "$tmp/log"; then
        pass "the installed vectors/check.py passes the installed materia-query$suffix (matte default)"
    else
        fail "the installed vectors/check.py against materia-query$suffix:"; cat "$tmp/log"
    fi
else
    echo "SKIP install: python3 (3.6 or later) not installed: the installed vectors/check.py was not run"
fi
if readelf -d "$root$prefix/lib/lib$name.so" 2>/dev/null | grep -q "SONAME.*\[lib$name.so.0\]"; then
    pass "lib$name.so has the soname lib$name.so.0"
else
    fail "lib$name.so's soname is not lib$name.so.0"
fi

cat > "$tmp/prog.c" <<'PROG'
#include <materia.h>
#include <stdio.h>
int main(void)
{
    mt_arena *a = mt_arena_create(0);
    mt_error err;
    mt_diffgeom dg = mt_diffgeom_default();
    mt_bsdf *b = mt_bsdf_create(a, MT_MODE_PBRT_V2, &dg, dg.n, 1, &err);
    mt_rgb f;
    if (!b || mt_bsdf_add(b, mt_lambertian_create(a, MT_MODE_PBRT_V2, mt_rgb_gray(0.5f), &err), &err)) return 1;
    f = mt_bsdf_f(b, mt_v3(0, 0, 1), mt_v3(0, 0.6f, 0.8f), MT_BSDF_ALL);
    printf("%s %s %d %.6f\n", mt_version(), mt_precision(), (int)sizeof(mt_real), (double)f.c[0]);
    mt_arena_destroy(a);
    return 0;
}
PROG
want="$(sed -n 's/^VERSION *:= *//p' Makefile) $precision $([ "$precision" = double ] && echo 8 || echo 4) 0.159155"
pc() { PKG_CONFIG_PATH=$root$prefix/lib/pkgconfig PKG_CONFIG_LIBDIR=$root$prefix/lib/pkgconfig \
       PKG_CONFIG_SYSROOT_DIR=$root ${PKG_CONFIG:-pkg-config} "$@" "$name"; }
cflags=$(pc --cflags) && libs=$(pc --libs) && slibs=$(pc --static --libs) || fail "pkg-config $name"
# shellcheck disable=SC2086
if $cc -std=c99 $cflags "$tmp/prog.c" -o "$tmp/prog" $libs >"$tmp/log" 2>&1 &&
   got=$(LD_LIBRARY_PATH=$root$prefix/lib "$tmp/prog") && [ "$got" = "$want" ]; then
    pass "a program built with pkg-config --cflags --libs $name runs against lib$name.so: $got"
else
    fail "the program against lib$name.so: \"${got:-}\", want \"$want\""; cat "$tmp/log"
fi
# the shared program needs lib$name.so.0; the static one must not (the
# archive and the shared library sit side by side: materia.pc.in says how
# the flags choose)
needed() { readelf -d "$1" 2>/dev/null | grep -c "NEEDED.*\[lib$name\.so"; }
if [ -x "$tmp/prog" ] && [ "$(needed "$tmp/prog")" = 1 ]; then
    pass "pkg-config --libs $name links lib$name.so.0 (NEEDED)"
else
    fail "pkg-config --libs $name: the program does not need lib$name.so.0"
fi
# shellcheck disable=SC2086
if $cc -std=c99 $cflags "$tmp/prog.c" -o "$tmp/prog-static" $slibs >"$tmp/log" 2>&1 &&
   got=$(env -u LD_LIBRARY_PATH "$tmp/prog-static") && [ "$got" = "$want" ] &&
   [ "$(needed "$tmp/prog-static")" = 0 ]; then
    pass "a program built with pkg-config --static --libs $name links lib$name.a, not the shared library: $got"
else
    fail "the program built with pkg-config --static --libs $name ($slibs): \"${got:-}\", want \"$want\" without lib$name.so"
    readelf -d "$tmp/prog-static" 2>/dev/null | grep NEEDED; cat "$tmp/log"
fi

if $make --no-print-directory uninstall DESTDIR="$root" PREFIX=$prefix BUILD="$build" PRECISION="$precision" \
    >"$tmp/log" 2>&1; then
    left=$(find "$root" ! -type d | sed "s|^$root||")
    if [ -z "$left" ]; then pass "make uninstall removes every installed file"
    else fail "make uninstall left:$(echo $left)"; fi
else
    fail "make uninstall failed:"; cat "$tmp/log"
fi
exit $status
