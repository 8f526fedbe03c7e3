#!/bin/sh
# The speed/accuracy trade report (make tradeoff; docs/TRADEOFF.md): runs each
# measurement script tradeoff/N-name.sh in order and joins their sections into
# OUT/report.md. Every script runs even when an earlier one failed; the exit
# status is non-zero when any failed.
#
# usage: run-tradeoff.sh FLOAT_BUILD DOUBLE_BUILD OUT
# environment: QUICK=1 (reduced sizes), TRADEOFF_ONLY=1,5 (a subset, by
# number), GNUPLOT (path of gnuplot; found on PATH when unset, "" for none).
#
# Each script is given: MT_BIN, MT_BIN_DOUBLE (the builds' bin directories),
# MT_TRADEOFF, MT_TRADEOFF_DOUBLE (their tradeoff program directories), OUT,
# QUICK (0 or 1), SHARED (../shared or empty), GNUPLOT (path or empty),
# TRADEOFF_DIR (tradeoff/). It writes OUT/N-name*.csv, OUT/N-name*.png when
# GNUPLOT is set, and OUT/N-name.md, its section of the report.
fbuild=$1; dbuild=$2; out=$3
if [ -z "$fbuild" ] || [ -z "$dbuild" ] || [ -z "$out" ]; then
    echo "usage: run-tradeoff.sh FLOAT_BUILD DOUBLE_BUILD OUT" >&2
    exit 2
fi
here=$(cd "$(dirname "$0")/.." && pwd) || exit 1
abs() { case $1 in /*) printf '%s\n' "$1" ;; *) printf '%s\n' "$(pwd)/$1" ;; esac; }
mkdir -p "$out" || exit 1
out=$(cd "$out" && pwd) || exit 1
fbuild=$(abs "$fbuild"); dbuild=$(abs "$dbuild")
for b in "$fbuild" "$dbuild"; do
    if [ ! -d "$b/tradeoff" ]; then
        echo "run-tradeoff.sh: $b/tradeoff: no such directory (make tradeoff builds it)" >&2
        exit 2
    fi
done

QUICK=${QUICK:-0}
case $QUICK in 0|1) ;; *) echo "run-tradeoff.sh: QUICK must be 0 or 1, not '$QUICK'" >&2; exit 2 ;; esac
if [ "${GNUPLOT+set}" != set ]; then GNUPLOT=$(command -v gnuplot 2>/dev/null || true); fi
SHARED=""
if [ -d "$here/../shared" ]; then SHARED=$(cd "$here/../shared" && pwd); fi
MT_BIN=$fbuild/bin MT_BIN_DOUBLE=$dbuild/bin MT_TRADEOFF=$fbuild/tradeoff MT_TRADEOFF_DOUBLE=$dbuild/tradeoff
OUT=$out TRADEOFF_DIR=$here/tradeoff
export MT_BIN MT_BIN_DOUBLE MT_TRADEOFF MT_TRADEOFF_DOUBLE OUT QUICK SHARED GNUPLOT TRADEOFF_DIR

selected() {
    [ -z "${TRADEOFF_ONLY:-}" ] && return 0
    case ",$TRADEOFF_ONLY," in *",$1,"*) return 0 ;; esac
    return 1
}

status=0; failed=""; sections=""
for script in "$here"/tradeoff/[0-9]-*.sh; do
    [ -f "$script" ] || continue
    name=$(basename "$script" .sh)
    n=${name%%-*}
    selected "$n" || continue
    echo "== $name"
    start=$(date +%s)
    rm -f "$out/$name.md"
    if sh "$script"; then
        echo "== $name: done in $(( $(date +%s) - start )) s"
    else
        echo "== $name: FAILED (status $?) after $(( $(date +%s) - start )) s"
        failed="$failed $name"; status=1
        if [ ! -s "$out/$name.md" ]; then
            printf '## %s\n\nThis measurement failed in this run (see the output of `make tradeoff`).\n' "$name" >"$out/$name.md"
        fi
    fi
    sections="$sections $name"
done

report=$out/report.md
{
    echo "# materia: the speed/accuracy trade"
    echo
    echo "| | |"
    echo "|---|---|"
    echo "| machine | $(uname -m), $(nproc 2>/dev/null || echo '?') cores, $(uname -sr) |"
    echo "| load average at the end | $(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo unknown) |"
    echo "| date | $(date -u '+%Y-%m-%d %H:%M UTC') |"
    echo "| command | \`make tradeoff$( [ "$QUICK" = 1 ] && echo ' QUICK=1')$( [ -n "${TRADEOFF_ONLY:-}" ] && echo " TRADEOFF_ONLY=$TRADEOFF_ONLY")\` |"
    echo "| QUICK | $QUICK |"
    echo "| gnuplot | ${GNUPLOT:-not found: the sections name the CSV files and the command that plots them} |"
    [ -n "$failed" ] && echo "| failed |$failed |"
    for name in $sections; do
        echo
        cat "$out/$name.md"
    done
} >"$report.tmp" && mv "$report.tmp" "$report"
echo "report: $report"
[ -n "$failed" ] && echo "failed:$failed"
exit $status
