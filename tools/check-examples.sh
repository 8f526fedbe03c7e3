#!/bin/sh
# make check's test of the embedding examples (examples/embed/, shown whole
# in docs/EMBEDDING.md): each .c program built as C99 (-std=c99 -Wall -Wextra
# -Wpedantic) and as C++17 (-Wall -Wextra), warnings being errors, against
# this build's headers and libmateria.a, run, its output compared with
# examples/embed/expected/NAME.txt (numbers within 1e-3 relative or 1e-4
# absolute: float and double builds print the same to that precision), and
# run under valgrind when it is installed (not in a sanitized build); each
# .cpp program likewise as C++17 only. Also checks that the README shows
# quick.c and docs/EMBEDDING.md every other program as it is. Prints
# PASS/FAIL/SKIP lines.
# usage: check-examples.sh BUILD_DIR   (CC, CXX, SANITIZE, EXAMPLE_LIBS from the environment)
build=$1
cc=${CC:-cc}; cxx=${CXX:-}
tmp=$(mktemp -d "${TMPDIR:-/tmp}/materia-examples.XXXXXX") || exit 1
trap 'rm -rf "$tmp"' EXIT INT TERM
status=0
san=${SANITIZE:+-fsanitize=$SANITIZE -fno-omit-frame-pointer}
inc="-Iinclude -I$build/include"
libs="$build/libmateria.a ${EXAMPLE_LIBS:--lpthread -lm}"
pass() { echo "PASS examples: $1"; }
fail() { echo "FAIL examples: $1"; status=1; }

vg=
if [ -n "${SANITIZE:-}" ]; then echo "SKIP examples under valgrind: a sanitized build (the sanitizers check them)"
elif command -v valgrind >/dev/null 2>&1; then vg=valgrind
else echo "SKIP examples under valgrind: valgrind is not installed"; fi
[ -n "$cxx" ] && command -v "$cxx" >/dev/null 2>&1 || { echo "SKIP examples as C++17: no C++ compiler"; cxx=; }

# same OUTPUT EXPECTED: every token equal, numbers within the tolerance
same() {
    awk 'NR == FNR { want[FNR] = $0; n = FNR; next }
         { got[FNR] = $0; m = FNR }
         END {
             if (n != m) exit 1
             for (i = 1; i <= n; i++) {
                 a = split(want[i], w, /[ ,()=]+/); b = split(got[i], g, /[ ,()=]+/)
                 if (a != b) exit 1
                 for (k = 1; k <= a; k++) {
                     if (w[k] == g[k]) continue
                     if (w[k] !~ /^-?[0-9.]+$/ || g[k] !~ /^-?[0-9.]+$/) exit 1
                     d = w[k] - g[k]; if (d < 0) d = -d
                     s = w[k] < 0 ? -w[k] : w[k]
                     if (d > 1e-4 && d > 1e-3 * s) exit 1
                 }
             }
         }' "$2" "$1"
}

# run NAME BINARY LANGUAGE
run() {
    want=examples/embed/expected/$1.txt
    if ! "$2" > "$tmp/$1.$3.out" 2> "$tmp/$1.$3.err"; then
        fail "$1 ($3) exited with status $?: $(cat "$tmp/$1.$3.err")"
    elif ! same "$tmp/$1.$3.out" "$want"; then
        fail "$1 ($3) printed:"; cat "$tmp/$1.$3.out"; echo "instead of $want:"; cat "$want"
    else
        pass "$1 ($3) runs and prints what $want holds"
    fi
}


for src in examples/embed/*.c examples/embed/*.cpp; do
    name=$(basename "${src%.*}")
    case $src in
    *.c)
        # shellcheck disable=SC2086
        if $cc -std=c99 -Wall -Wextra -Wpedantic -Werror $san $inc "$src" -o "$tmp/$name" $libs > "$tmp/log" 2>&1; then
            pass "$name.c builds as C99 without a warning"; run "$name" "$tmp/$name" c99
        else
            fail "$name.c as C99:"; cat "$tmp/log"
        fi ;;
    esac
    [ -n "$cxx" ] || continue
    # shellcheck disable=SC2086
    if $cxx -x c++ -std=c++17 -Wall -Wextra -Werror $san $inc "$src" -x none -o "$tmp/$name-cxx" $libs > "$tmp/log" 2>&1; then
        pass "$(basename "$src") builds as C++17 without a warning"; run "$name" "$tmp/$name-cxx" c++17
    else
        fail "$(basename "$src") as C++17:"; cat "$tmp/log"
    fi
    [ -n "$vg" ] || continue
    bin=$tmp/$name; [ -x "$bin" ] || bin=$tmp/$name-cxx
    [ -x "$bin" ] || continue
    if valgrind -q --error-exitcode=99 --leak-check=full --errors-for-leak-kinds=definite,indirect \
        "$bin" > /dev/null 2> "$tmp/vg.log"; then
        pass "$name runs valgrind-clean (no invalid access, no uninitialized read, no leak)"
    else
        fail "$name under valgrind:"; cat "$tmp/vg.log"
    fi
done

# the documentation shows the programs that are tested, line for line: the
# README the first, docs/EMBEDDING.md the others
for src in examples/embed/*.c examples/embed/*.cpp; do
    doc=docs/EMBEDDING.md
    [ "$src" = examples/embed/quick.c ] && doc=README.md
    if awk -v f="$src" 'BEGIN { while ((getline l < f) > 0) want = want l "\n" }
                        { doc = doc $0 "\n" } END { exit index(doc, want) ? 0 : 1 }' "$doc"; then
        pass "$doc shows $src as it is"
    else
        fail "$doc does not show $src as it is (copy it into the document)"
    fi
done
exit $status
