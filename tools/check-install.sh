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
         "$root$prefix/lib/pkgconfig/$name.pc" "$root$prefix/share/doc/$name/LICENSE" \
         "$root$prefix/share/doc/$name/README.md" "$root$prefix/share/doc/$name/ERRATA.md" \
         "$root$prefix/bin/materia-render$suffix" "$root$prefix/bin/materia-query$suffix" \
         "$root$prefix/bin/materia-conformance$suffix"; do
    [ -e "$f" ] || missing="$missing ${f#$root}"
done
if [ -z "$missing" ]; then pass "headers, lib$name.a/.so, $name.pc, the tools$suffix, docs and LICENSE installed"
else fail "not installed:$missing"; fi
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
slibs=$(echo " $slibs " | sed "s| -l$name | -Wl,-Bstatic -l$name -Wl,-Bdynamic |")
# shellcheck disable=SC2086
if $cc -std=c99 $cflags "$tmp/prog.c" -o "$tmp/prog-static" $slibs >"$tmp/log" 2>&1 &&
   got=$("$tmp/prog-static") && [ "$got" = "$want" ]; then
    pass "a program built with pkg-config --static --libs $name runs with lib$name.a: $got"
else
    fail "the program against lib$name.a: \"${got:-}\", want \"$want\""; cat "$tmp/log"
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
