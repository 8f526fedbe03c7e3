#!/bin/sh
# make check's link test: the programs of tests/link/ built against
# BUILD/libmateria.a pull in only what they use. A Lambertian built by hand,
# a plastic made from its kind's object and a material made from a pbrt-v2
# statement link with -lpthread -lm alone (no OpenEXR, no libpng) and print
# their value; the plastic's program holds no other material kind and the
# Lambertian's no material at all. The README's program (a material from
# text, examples/embed/quick.c) links with -lpthread -lm alone too. Prints PASS/FAIL lines for
# tools/run-checks.sh, and the objects each program took from the archive
# (docs/LINKING.md has the table and the commands).
# usage: check-link.sh BUILD_DIR   (CC from the environment)
build=$1
cc=${CC:-cc}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/materia-link.XXXXXX") || exit 1
trap 'rm -rf "$tmp"' EXIT INT TERM
status=0
pass() { echo "PASS link: $1"; }
fail() { echo "FAIL link: $1"; status=1; }

# the material kinds, from the registry itself
kinds=$("$build/bin/materia-query" --list materials | awk '{ print $1 }')
[ -n "$kinds" ] || { fail "materia-query --list materials gave nothing"; exit 1; }

# name  expected output
for p in "lambertian 0.159155" "plastic 0.180443" "statement 0.357339"; do
    name=${p%% *}; want=${p#* }
    if ! $cc -std=c99 -Iinclude -I"$build/include" "tests/link/$name.c" -o "$tmp/$name" \
        "$build/libmateria.a" -lpthread -lm >"$tmp/$name.log" 2>&1; then
        fail "$name: does not link with -lpthread -lm alone:"
        sed 's/^/  /' "$tmp/$name.log" | head -n 20
        continue
    fi
    got=$("$tmp/$name")
    if [ "$got" = "$want" ]; then pass "$name: links with -lpthread -lm alone (no OpenEXR, no libpng) and prints $got"
    else fail "$name: printed \"$got\", want \"$want\""; fi
    # the objects it took from the archive (GNU ld prints them with -t -t)
    if $cc -std=c99 -Iinclude -I"$build/include" "tests/link/$name.c" -o "$tmp/$name.t" \
        "$build/libmateria.a" -lpthread -lm -Wl,-t -Wl,-t >"$tmp/$name.trace" 2>/dev/null; then
        echo "# $name: $(grep -c 'libmateria\.a)' "$tmp/$name.trace") objects of libmateria.a"
    fi
    # the material kinds in it, by their objects' symbols
    have=
    for k in $kinds; do
        nm "$tmp/$name" 2>/dev/null | grep -q " mt_${k}_material\$" && have="$have $k"
    done
    case $name in
    lambertian) [ -z "$have" ] && pass "lambertian: no material kind linked" ||
                    fail "lambertian: material kinds linked:$have" ;;
    plastic) [ "$have" = " plastic" ] && pass "plastic: the plastic kind alone linked" ||
                 fail "plastic: material kinds linked:$have (want plastic alone)" ;;
    esac
done
# the README's program: every kind (a type named by a string), no image library
if $cc -std=c99 -Iinclude -I"$build/include" examples/embed/quick.c -o "$tmp/quick" \
    "$build/libmateria.a" -lpthread -lm >"$tmp/quick.log" 2>&1; then
    got=$("$tmp/quick")
    case $got in
    "f = "*) pass "the README's program (examples/embed/quick.c): links with -lpthread -lm alone and runs" ;;
    *) fail "the README's program printed \"$got\"" ;;
    esac
else
    fail "the README's program (examples/embed/quick.c) does not link with -lpthread -lm alone:"
    sed 's/^/  /' "$tmp/quick.log" | head -n 20
fi
exit $status
