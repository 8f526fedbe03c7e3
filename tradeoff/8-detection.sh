#!/bin/sh
# 8. Detection curves: the size EPS of a smooth error planted in an
# implementation (tests/plugin_planted.c) against the fraction of seeded
# runs that catch it, for the suite's two paths and for Mitsuba 3's own
# chi-square test run on the same plugin (docs/TRADEOFF.md, "Detection
# curves"). Each point is one bench/power.sh call (the physics checks alone,
# --compare none, one configuration, --seed 1..SEEDS) or one
# tradeoff/mitsuba_detection.py call. Expensive (tens of minutes at the full
# size): never part of make check.
#
# Curves (DET_CURVES, any of):
#   lib-power     the plugin in this process, --power 0.01 --quick
#   lib-default   the plugin in this process, the suite's defaults
#   text-default  the plugin through materia-plugin-host (the text protocol),
#                 the suite's defaults
#   mitsuba       mitsuba.chi2.ChiSquareTest as Mitsuba's BSDF tests run it,
#                 at the suite's --quick incoming directions; skipped with a
#                 message when MITSUBA_PYTHON (default python3) has no mitsuba
#
# Environment: MT_BIN (a build's bin directory: tools/run-tradeoff.sh sets it)
# or DET_BUILD (the build directory, e.g. build/float), OUT (output
# directory), QUICK (1: matte only, 3 EPS and 3 seeds a curve), GNUPLOT (path or empty; found on
# PATH when unset), MITSUBA_PYTHON, DET_CURVES, DET_CONFIGS (|-separated
# names, default "matte Kd=1|plastic default"), DET_KIND (warp; pdf or f
# plant the other classes), DET_SEEDS (seeds a point for every curve, else
# each curve's own: lib-power 20, lib-default 40, text-default 10,
# mitsuba 40; DET_SEEDS_LIB_POWER etc. set one curve's), DET_EPS_LIB_POWER, DET_EPS_DEFAULT, DET_EPS_MITSUBA (the EPS
# lists), DET_LABEL (what the curves were made at, in the CSV and the report;
# default the source's git commit), DET_KEEP (an earlier 8-detection.csv:
# its rows of the curves not in DET_CURVES are kept, so that one curve can
# be measured again on another build and plotted with the others; with
# DET_CURVES=" " it only draws).
# Writes OUT/8-detection.csv (one row a point: curve, configuration, kind,
# eps, caught, runs, rate, its 95% Wilson interval, seconds, load average,
# label),
# 8-detection.png and 8-detection.md.
#
#   DET_BUILD=build/float OUT=build/tradeoff sh tradeoff/8-detection.sh
set -u
if [ "${1:-}" = --help ] || [ "${1:-}" = -h ]; then
    sed -n '2,/^set -u/p' "$0" | sed '$d' | sed 's/^# \{0,1\}//'
    exit 0
fi
[ $# -eq 0 ] || { echo "$0: no arguments but --help (the environment sets everything)" >&2; exit 2; }
TRADEOFF_DIR=${TRADEOFF_DIR:-$(cd "$(dirname "$0")" && pwd)}
. "$TRADEOFF_DIR/lib.sh"
abspath() { case $1 in /*) echo "$1" ;; *) echo "$PWD/$1" ;; esac; }
if [ -n "${DET_BUILD:-}" ]; then BUILD=$(abspath "$DET_BUILD")
elif [ -n "${MT_BIN:-}" ]; then BUILD=$(abspath "$MT_BIN/..")
else tr_die "set DET_BUILD (a build directory, e.g. build/float) or MT_BIN"; fi
: "${OUT:?set OUT, the output directory}"
OUT=$(abspath "$OUT")
QUICK=${QUICK:-0}
if [ "${GNUPLOT+set}" != set ]; then GNUPLOT=$(command -v gnuplot 2>/dev/null || true); fi
POWER_SH=$TRADEOFF_DIR/../bench/power.sh
PLUGIN=$BUILD/tests/plugin_planted.so
tr_need "$BUILD/bin/materia-conformance" "$BUILD/bin/materia-plugin-host"
[ -f "$PLUGIN" ] || tr_die "$PLUGIN: not built (make tests builds it)"
CURVES=${DET_CURVES:-"lib-power lib-default text-default mitsuba"}
KIND=${DET_KIND:-warp}
if [ "$QUICK" = 1 ]; then # a few minutes: one configuration, three points a curve
    CONFIGS=${DET_CONFIGS:-"matte Kd=1"}
    EPS_LIB_POWER=${DET_EPS_LIB_POWER:-"0.005 0.01 0.02"}
    EPS_DEFAULT=${DET_EPS_DEFAULT:-"0.01 0.02 0.05"}
    EPS_MITSUBA=${DET_EPS_MITSUBA:-"0.01 0.02 0.05"}
else
    CONFIGS=${DET_CONFIGS:-"matte Kd=1|plastic default"}
    EPS_LIB_POWER=${DET_EPS_LIB_POWER:-"0.0025 0.005 0.01 0.02"}
    EPS_DEFAULT=${DET_EPS_DEFAULT:-"0.005 0.01 0.02 0.05 0.1"}
    EPS_MITSUBA=${DET_EPS_MITSUBA:-"0.005 0.01 0.02 0.05 0.1"}
fi
MPY=${MITSUBA_PYTHON:-python3}
LABEL=${DET_LABEL:-"commit $(git -C "$TRADEOFF_DIR/.." rev-parse --short HEAD 2>/dev/null || echo unknown)"}
seeds_of() {
    _so=$(eval "echo \"\${DET_SEEDS_$(printf '%s' "$1" | tr 'a-z-' 'A-Z_'):-}\"")
    if [ -n "$_so" ]; then echo "$_so"; return; fi
    if [ -n "${DET_SEEDS:-}" ]; then echo "$DET_SEEDS"; return; fi
    if [ "$QUICK" = 1 ]; then echo 3; return; fi
    case $1 in lib-power) echo 20 ;; lib-default) echo 40 ;; text-default) echo 10 ;; *) echo 40 ;; esac
}
CSV=$OUT/8-detection.csv
MD=$OUT/8-detection.md
mkdir -p "$OUT" || exit 1
TMP=$(mktemp -d "${TMPDIR:-/tmp}/mt-detection.XXXXXX") || exit 1
trap 'rm -rf "$TMP"' EXIT
trap 'exit 1' INT TERM

MITSUBA=0
if printf '%s\n' "$CURVES" | grep -qw mitsuba; then
    if "$MPY" -c 'import mitsuba, numpy' 2>/dev/null; then MITSUBA=1
    else echo "8-detection: Mitsuba 3 not found (MITSUBA_PYTHON=$MPY has no mitsuba/numpy): no Mitsuba curve" >&2; fi
fi

# one point: prints "caught/runs seconds"
point() { # curve config kind eps seeds
    case $1 in
    lib-power) sh "$POWER_SH" "$BUILD" lib "$2" "$3" "$4" "$5" --power 0.01 --quick ;;
    lib-default) sh "$POWER_SH" "$BUILD" lib "$2" "$3" "$4" "$5" ;;
    text-default) sh "$POWER_SH" "$BUILD" text "$2" "$3" "$4" "$5" ;;
    mitsuba) "$MPY" "$TRADEOFF_DIR/mitsuba_detection.py" "$PLUGIN" "$2" "$3" "$4" "$5" ;;
    esac | awk -F'\t' 'NF >= 6 { print $5, $6 }'
}

echo "curve,config,kind,eps,caught,runs,rate,lo95,hi95,seconds,load,label" >"$TMP/csv"
if [ -n "${DET_KEEP:-}" ]; then
    [ -f "$DET_KEEP" ] || tr_die "DET_KEEP=$DET_KEEP: no such file"
    awk -F, -v run=" $CURVES " 'NR > 1 && index(run, " " $1 " ") == 0' "$DET_KEEP" >>"$TMP/csv"
fi
status=0
for curve in $CURVES; do
    case $curve in
    lib-power) epss=$EPS_LIB_POWER ;;
    lib-default | text-default) epss=$EPS_DEFAULT ;;
    mitsuba) [ $MITSUBA = 1 ] || continue; epss=$EPS_MITSUBA ;;
    *) tr_die "DET_CURVES: unknown curve '$curve'" ;;
    esac
    seeds=$(seeds_of "$curve")
    IFS='|'; set -- $CONFIGS; unset IFS
    for config in "$@"; do
        # eps 0: the honest plugin (kind none), the false-rejection rate
        for eps in 0 $epss; do
            kind=$KIND; [ "$eps" = 0 ] && kind=none
            r=$(point "$curve" "$config" "$kind" "$eps" "$seeds")
            load=$(cut -d' ' -f1 /proc/loadavg 2>/dev/null || echo NA)
            if [ -z "$r" ]; then
                echo "8-detection: $curve '$config' $kind $eps: no result" >&2; status=1; continue
            fi
            echo "8-detection: $curve '$config' $kind $eps: $r (load $load)" >&2
            echo "$r" | awk -v c="$curve" -v cf="$config" -v k="$kind" -v e="$eps" -v l="$load" -v lb="$(printf '%s' "$LABEL" | tr ',' ';')" '{
                split($1, a, "/"); x = a[1]; n = a[2]; p = x / n; z = 1.959964
                d = 1 + z * z / n; m = (p + z * z / (2 * n)) / d; h = z * sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / d
                printf "%s,%s,%s,%s,%d,%d,%.4f,%.4f,%.4f,%s,%s,%s\n", c, cf, k, e, x, n, p, (m - h < 0 ? 0 : m - h), (m + h > 1 ? 1 : m + h), $2, l, lb }' \
                >>"$TMP/csv"
        done
    done
done
mv "$TMP/csv" "$CSV"

# one data file per (curve, configuration), planted points only
slug() { printf '%s' "$1" | tr -c 'A-Za-z0-9' '_'; }
# a panel per configuration in the CSV (kept rows too), in order
IFS='|'; set -- $(awk -F, 'NR > 1 && !seen[$2]++ { printf "%s%s", (n++ ? "|" : ""), $2 }' "$CSV"); unset IFS
panels=0; plots=""
titles="lib-power:in-process --power 0.01|lib-default:in-process defaults|text-default:text protocol defaults|mitsuba:Mitsuba 3 chi2 test"
for config in "$@"; do
    items=""; ls=0
    for curve in lib-power lib-default text-default mitsuba; do
        ls=$((ls + 1))
        f=8-detection-$curve-$(slug "$config").csv
        awk -F, -v c="$curve" -v cf="$config" 'NR > 1 && $1 == c && $2 == cf && $4 + 0 > 0' "$CSV" >"$OUT/$f"
        [ -s "$OUT/$f" ] || { rm -f "$OUT/$f"; continue; }
        honest=$(awk -F, -v c="$curve" -v cf="$config" '$1 == c && $2 == cf && $4 + 0 == 0 { print $5 "/" $6 }' "$CSV")
        t=$(printf '%s\n' "$titles" | tr '|' '\n' | awk -F: -v c="$curve" '$1 == c { print $2 }')
        item="'$f' using 4:7:8:9 with yerrorlines ls $ls title '$t (honest ${honest:-?})'"
        if [ -z "$items" ]; then items=$item; else items="$items, \\
     $item"; fi
    done
    [ -n "$items" ] || continue
    panels=$((panels + 1))
    plots="$plots
set title '$config: a planted $KIND of relative size EPS'
plot $items"
done
plot=$(tr_plot 8-detection "Detection curves: planted error size against detection rate" "8-detection.csv" "
set multiplot layout 1,$panels
set xlabel 'EPS (relative size of the planted error)'
set ylabel 'fraction of seeded runs that fail (honest: false rejections)'
eval logx
set xrange [0.0018:0.3]
set yrange [-0.03:1.03]
set key bottom right font ',8'
set arrow from graph 0, first 0.95 to graph 1, first 0.95 nohead dt 2 lc rgb '#888888'
$plots
unset multiplot
" "size 1200,520 font 'DejaVu Sans,9'") || status=1

{
    echo "## 8. Detection curves"
    echo
    echo "$(uname -m), $(nproc 2>/dev/null || echo '?') cores, load average at the end $(cut -d' ' -f1-3 /proc/loadavg 2>/dev/null || echo unknown); each curve made at:"
    awk -F, 'NR > 1 && !seen[$1 FS $12]++ { printf "%s%s: %s", (n++ ? "; " : ""), $1, $12 } END { print "." }' "$CSV"
    echo
    echo "$plot"
    echo
    echo "| curve | configuration | EPS | caught | seconds | load average |"
    echo "|---|---|---|---|---|---|"
    awk -F, 'NR > 1 { printf "| %s | %s | %s%s | %d/%d | %s | %s |\n", $1, $2, $4, ($3 == "none" ? " (honest)" : ""), $5, $6, $10, $11 }' "$CSV"
    [ $MITSUBA = 1 ] || ! printf '%s\n' "$CURVES" | grep -qw mitsuba ||
        echo "Mitsuba 3 was not found (set MITSUBA_PYTHON to a Python with mitsuba and numpy): no Mitsuba curve."
} >"$MD"
exit $status
