#!/bin/sh
# Runs every test binary and the conformance suite, counts the PASS/FAIL lines
# they print, and ends with "N passed, N failed". Exit status 1 on any failure
# (a FAIL line, or a binary that exits non-zero or crashes).
# usage: run-checks.sh BUILD_DIR PRECISION TEST_BINARY...
#
# The programs run CHECK_JOBS at a time (default: the number of processors),
# the longest first; each one's output is printed whole, in the order they
# were listed, as soon as it and those before it have finished, so the log
# reads the same whatever the number of jobs. Progress goes to standard
# error as each program ends, in the order they end: "[ 7/64] test_bump:
# 8 passed, 0 failed (2.1 s)", and every minute without one, what is still
# running: "[ 6/64] running: test_pbrt_renders (4 min), materia-conformance
# (5 min)", so that a long run is never silent. CHECK_JOBS=1 runs them one
# after the other. CHECK_TIMES=FILE writes each program's wall and CPU
# seconds (user + system, itself and its children) there, as TSV: what to
# look at when the run grows. CHECK_SKIP="NAME ..." leaves those programs
# out, each reported as a SKIP line (CI runs the pbrt-v2 renders in one of its
# builds only: .ci/run says why).
build=$1; precision=$2; shift 2
dir=$(mktemp -d "${TMPDIR:-/tmp}/materia-check.XXXXXX") || exit 1
trap 'rm -rf "$dir"' EXIT INT TERM
jobs=${CHECK_JOBS:-$(nproc 2>/dev/null || getconf _NPROCESSORS_ONLN 2>/dev/null || echo 1)}
n=0
# quote: one argument as a single-quoted shell word
quote() { printf "'%s'" "$(printf '%s' "$1" | sed "s/'/'\\\\''/g")"; }
# job NAME COMMAND...: one entry of the run, written as a script of its own
job() {
    n=$((n + 1))
    printf '%s\n' "$1" > "$dir/$n.name"
    case " ${CHECK_SKIP:-} " in
    *" $1 "*) echo "echo 'SKIP $1: left out of this run by CHECK_SKIP'" > "$dir/$n.sh"; return ;;
    esac
    shift
    { for a in "$@"; do quote "$a"; printf ' '; done; echo; } > "$dir/$n.sh"
}
# the conformance suite and the tests that render or drive child processes
# take minutes; they start first so that the short ones fill the gaps
for t in "$@"; do
    case $(basename "$t") in test_impl|test_golden|test_pbrt_renders|test_dipole|test_render_*) job "$(basename "$t")" "$t" ;; esac
done
# shellcheck disable=SC2086
job materia-conformance "$build/bin/materia-conformance" ${CONF_ARGS:-}
for t in "$@"; do
    case $(basename "$t") in test_impl|test_golden|test_pbrt_renders|test_dipole|test_render_*) ;; *) job "$(basename "$t")" "$t" ;; esac
done
# the embedding examples (examples/embed/, docs/EMBEDDING.md): built as C99
# and C++17, run, their output checked, under valgrind when it is installed
job examples sh tools/check-examples.sh "$build"
# docs/REFERENCE.md against the tables it is generated from
[ -n "${REF_GEN:-}" ] && job reference "$REF_GEN" --check docs/REFERENCE.md
# make install into a temporary directory and a program built against it
# (not under the sanitizers: a program linking the library would need them)
[ -z "${SANITIZE:-}" ] && job check-install sh tools/check-install.sh "$build" "$precision"
# programs that use a BxDF, a material, the statement parser link only that
# (tools/check-link.sh; not sanitized either, for the same reason)
[ -z "${SANITIZE:-}" ] && job check-link sh tools/check-link.sh "$build"
# the amalgamation builds alone, and programs from it run (C and C++)
job check-amalgamation sh tools/check-amalgamation.sh

# the runner: each job's output goes to N.log, its exit status to N.rc
i=0
while [ "$i" -lt "$n" ]; do i=$((i + 1)); echo "$i"; done |
    xargs -P "$jobs" -I{} sh -c 't0=$(date +%s.%N); echo "$t0" > "$1/$2.start"
        sh "$1/$2.sh" > "$1/$2.log" 2>&1; rc=$?
        { echo "$t0 $(date +%s.%N)"; times; } > "$1/$2.time"
        echo $rc > "$1/$2.rc.tmp"; mv "$1/$2.rc.tmp" "$1/$2.rc"' sh "$dir" {} &
runner=$!

echo "make check: $n programs, $jobs at a time" >&2
# progress: each program that has ended and was not announced yet, to
# standard error (its output itself comes in order on standard output)
done_count=0
last=$(date +%s)
announce() {
    k=0
    while [ "$k" -lt "$n" ]; do
        k=$((k + 1))
        [ -f "$dir/$k.rc" ] && [ ! -f "$dir/$k.ann" ] || continue
        : > "$dir/$k.ann"
        done_count=$((done_count + 1))
        awk -v k="$done_count" -v n="$n" -v name="$(cat "$dir/$k.name")" -v rc="$(cat "$dir/$k.rc")" '
            /^PASS/ { p++ } /^FAIL/ { f++ } /^XFAIL/ { x++ } /^SKIP/ { s++ }
            END {
                t = ""; getline line < TIMEF; split(line, a, " "); if (a[2] > a[1]) t = sprintf(" (%.1f s)", a[2] - a[1])
                printf "[%" length(n) "d/%d] %s: %d passed, %d failed%s%s%s%s\n", k, n, name, p, f,
                    x ? sprintf(", %d expected failures", x) : "", s ? sprintf(", %d skipped", s) : "",
                    rc != 0 && f == 0 ? sprintf(", exit status %d", rc) : "", t
            }' TIMEF="$dir/$k.time" "$dir/$k.log" >&2
        last=$(date +%s)
    done
    now=$(date +%s)
    [ $((now - last)) -ge 60 ] || return 0
    last=$now
    running=
    k=0
    while [ "$k" -lt "$n" ]; do
        k=$((k + 1))
        [ -f "$dir/$k.start" ] && [ ! -f "$dir/$k.rc" ] || continue
        running="$running${running:+, }$(cat "$dir/$k.name") ($(( (now - $(cut -d. -f1 "$dir/$k.start")) / 60 )) min)"
    done
    [ -n "$running" ] && printf '[%*s/%d] running: %s\n' "${#n}" "$done_count" "$n" "$running" >&2
    return 0
}
passed=0; failed=0; xfailed=0; skipped=0
i=0
while [ "$i" -lt "$n" ]; do
    i=$((i + 1))
    announce
    while [ ! -f "$dir/$i.rc" ]; do
        if ! kill -0 "$runner" 2>/dev/null && [ ! -f "$dir/$i.rc" ]; then
            echo "FAIL $(cat "$dir/$i.name"): the runner stopped before it finished"
            echo 125 > "$dir/$i.rc"
            break
        fi
        sleep 1
        announce
    done
    log=$dir/$i.log; rc=$(cat "$dir/$i.rc")
    [ -f "$log" ] && cat "$log" || : > "$log"
    p=$(grep -c '^PASS' "$log"); f=$(grep -c '^FAIL' "$log")
    x=$(grep -c '^XFAIL' "$log"); s=$(grep -c '^SKIP' "$log")
    passed=$((passed + p)); failed=$((failed + f)); xfailed=$((xfailed + x)); skipped=$((skipped + s))
    if [ "$rc" -ne 0 ] && [ "$f" -eq 0 ]; then
        echo "FAIL $(cat "$dir/$i.name"): exited with status $rc"
        failed=$((failed + 1))
    fi
done
wait "$runner" 2>/dev/null
if [ -n "${CHECK_TIMES:-}" ]; then
    # N.time: start and end, then times's two lines (the job shell's own
    # user and system time, then its children's, as 0m1.234s)
    i=0
    { printf 'program\twall_s\tcpu_s\n'
      while [ "$i" -lt "$n" ]; do
          i=$((i + 1))
          [ -f "$dir/$i.time" ] || continue
          awk -v name="$(cat "$dir/$i.name")" '
              function s(x) { split(x, a, "m"); sub("s", "", a[2]); return a[1] * 60 + a[2] }
              NR == 1 { wall = $2 - $1 } NR == 3 { printf "%s\t%.1f\t%.1f\n", name, wall, s($1) + s($2) }' "$dir/$i.time"
      done; } > "$CHECK_TIMES"
fi
if [ -n "${SANITIZE:-}" ]; then
    echo "SKIP install: not tested in a sanitized build"
    echo "SKIP link: not tested in a sanitized build"
    skipped=$((skipped + 2))
fi
if [ -n "${CXX_SKIP:-}" ]; then
    echo "SKIP c++ program: $CXX_SKIP"
    skipped=$((skipped + 1))
fi
echo "precision $precision: $xfailed expected failures (pbrt-v2 errata), $skipped skipped"
echo "$passed passed, $failed failed"
[ "$failed" -eq 0 ]
