#!/bin/sh
# Runs every test binary and the conformance suite, counts the PASS/FAIL lines
# they print, and ends with "N passed, N failed". Exit status 1 on any failure
# (a FAIL line, or a binary that exits non-zero or crashes).
# usage: run-checks.sh BUILD_DIR PRECISION TEST_BINARY...
build=$1; precision=$2; shift 2
passed=0; failed=0; xfailed=0; skipped=0
log=$(mktemp "${TMPDIR:-/tmp}/materia-check.XXXXXX") || exit 1
trap 'rm -f "$log"' EXIT INT TERM
run() {
    name=$1; shift
    "$@" >"$log" 2>&1
    rc=$?
    cat "$log"
    p=$(grep -c '^PASS' "$log"); f=$(grep -c '^FAIL' "$log")
    x=$(grep -c '^XFAIL' "$log"); s=$(grep -c '^SKIP' "$log")
    passed=$((passed + p)); failed=$((failed + f)); xfailed=$((xfailed + x)); skipped=$((skipped + s))
    if [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then
        echo "FAIL $name: exited with status $rc"
        failed=$((failed + 1))
    fi
}
for t in "$@"; do
    run "$(basename "$t")" "$t"
done
# docs/REFERENCE.md against the tables it is generated from
if [ -n "${REF_GEN:-}" ]; then
    run reference "$REF_GEN" --check docs/REFERENCE.md
fi
# make install into a temporary directory and a program built against it
# (not under the sanitizers: a program linking the library would need them)
if [ -n "${SANITIZE:-}" ]; then
    echo "SKIP install: not tested in a sanitized build"
    skipped=$((skipped + 1))
else
    run check-install sh tools/check-install.sh "$build" "$precision"
fi
if [ -n "${CXX_SKIP:-}" ]; then
    echo "SKIP c++ program: $CXX_SKIP"
    skipped=$((skipped + 1))
fi
# shellcheck disable=SC2086
run materia-conformance "$build/bin/materia-conformance" ${CONF_ARGS:-}
echo "precision $precision: $xfailed expected failures (pbrt-v2 errata), $skipped skipped"
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
