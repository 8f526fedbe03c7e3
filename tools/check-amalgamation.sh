#!/bin/sh
# make check's amalgamation test: tools/amalgamate.sh writes materia.c and
# materia.h into a temporary directory; materia.c compiles alone with
# `cc -std=c99 -c materia.c` (no warning), warning-free under -Wall -Wextra
# -Wpedantic in float and double, and with the image formats switched on
# when OpenEXR and libpng are installed; a C program and a C++ program
# (the header under -std=c++17 -Wall -Wextra -pedantic) built from them
# make a material from a statement and print its value, which must be the
# library's. About 10 s of CPU time. Prints PASS/FAIL/SKIP lines for
# tools/run-checks.sh.
# usage: check-amalgamation.sh   (CC, CXX from the environment; run from the source tree)
cc=${CC:-cc}
cxx=${CXX:-c++}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/materia-amalg-check.XXXXXX") || exit 1
trap 'rm -rf "$tmp"' EXIT INT TERM
status=0
pass() { echo "PASS amalgamation: $1"; }
fail() { echo "FAIL amalgamation: $1"; status=1; }
version=$(sed -n 's/^VERSION *:= *//p' Makefile)
warn="-Wall -Wextra -Wpedantic -Wshadow -Wstrict-prototypes -Wmissing-prototypes"

if ! sh tools/amalgamate.sh "$tmp" "$version" >"$tmp/log" 2>&1; then
    fail "tools/amalgamate.sh failed:"; cat "$tmp/log"; exit 1
fi
cd "$tmp" || exit 1

# built alone: nothing on the command line but -std=c99 -c, and silent
if $cc -std=c99 -c materia.c -o plain.o >log 2>&1 && [ ! -s log ]; then
    pass "cc -std=c99 -c materia.c builds alone, without a message"
else
    fail "cc -std=c99 -c materia.c:"; head -n 30 log
fi
for d in 0 1; do
    if $cc -std=c99 $warn -Werror -DMT_USE_DOUBLE=$d -c materia.c -o "m$d.o" >log 2>&1; then
        pass "materia.c with MT_USE_DOUBLE=$d: no warning under $warn"
    else
        fail "materia.c with MT_USE_DOUBLE=$d and $warn -Werror:"; head -n 30 log
    fi
done

# a C program from materia.h and materia.c: the statement program of
# tests/link, whose value the library gives too (tools/check-link.sh)
src=$OLDPWD
if $cc -std=c99 $warn -Werror -I. -c "$src/tests/link/statement.c" -o prog.o >log 2>&1 &&
   $cc prog.o m0.o -o prog -lpthread -lm >>log 2>&1 && got=$(./prog) && [ "$got" = 0.357339 ]; then
    pass "a C99 program built from materia.h and materia.c prints the library's value ($got)"
else
    fail "the C99 program: \"${got:-}\", want 0.357339:"; head -n 30 log
fi

# the same program as C++, against the amalgamated header
if command -v "$cxx" >/dev/null 2>&1; then
    if $cxx -std=c++17 -Wall -Wextra -pedantic -Werror -I. -x c++ -c "$src/tests/link/statement.c" -o progxx.o >log 2>&1 &&
       $cxx progxx.o m0.o -o progxx -lpthread -lm >>log 2>&1 && got=$(./progxx) && [ "$got" = 0.357339 ]; then
        pass "the program as C++17 (-Wall -Wextra -pedantic) against materia.h prints $got"
    else
        fail "the C++17 program: \"${got:-}\", want 0.357339:"; head -n 30 log
    fi
else
    echo "SKIP amalgamation: no C++ compiler ($cxx): the header was not built as C++"
fi

# a program that prints the formats it reads
cat > formats.c <<'PROG'
#include "materia.h"
#include <stdio.h>
int main(void) { printf("%s\n", mt_image_formats()); return 0; }
PROG
if $cc -std=c99 -I. formats.c m0.o -o formats0 -lpthread -lm >log 2>&1 && got=$(./formats0) && [ "$got" = pfm ]; then
    pass "by default the amalgamation reads PFM alone and links no image library"
else
    fail "the default amalgamation's formats: \"${got:-}\", want \"pfm\":"; head -n 30 log
fi
# the image formats switched on, where their libraries are installed
pc=${PKG_CONFIG:-pkg-config}
if $pc --exists OpenEXR libpng 2>/dev/null; then
    fmt_cflags="-I$($pc --variable=includedir OpenEXR) $($pc --cflags libpng)"
    fmt_libs="-L$($pc --variable=libdir OpenEXR) -lOpenEXRCore$($pc --variable=libsuffix OpenEXR) $($pc --libs libpng)"
    # shellcheck disable=SC2086
    if $cc -std=c99 $warn -Werror -DMATERIA_HAVE_EXR=1 -DMATERIA_HAVE_PNG=1 $fmt_cflags -c materia.c -o mf.o >log 2>&1 &&
       $cc -std=c99 -I. formats.c mf.o -o formats $fmt_libs -lpthread -lm >>log 2>&1 &&
       got=$(./formats) && [ "$got" = "exr png pfm" ]; then
        pass "MATERIA_HAVE_EXR=1 MATERIA_HAVE_PNG=1: builds warning-free and reads \"$got\""
    else
        fail "with the image formats: \"${got:-}\", want \"exr png pfm\":"; head -n 30 log
    fi
else
    echo "SKIP amalgamation: OpenEXR or libpng not installed: the image formats were not switched on"
fi
exit $status
