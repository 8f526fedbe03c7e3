#!/bin/sh
# Measurement 4: measured BRDFs. $MT_TRADEOFF/measured (tradeoff/measured.c)
# measures the error and the time per call of the irregular (.brdf, k-d
# search) and half-angle (MERL) forms of a BRDF, and of MERL tables at
# coarser resolutions ($OUT/4-measured-analytic.csv, and with ../shared
# 4-measured-files.csv for its real files); this script plots them
# (4-measured-size, -time: .gp, and .png with gnuplot) and writes the report
# section $OUT/4-measured.md. Environment: MT_TRADEOFF, OUT, QUICK, SHARED,
# GNUPLOT, TRADEOFF_DIR (tools/run-tradeoff.sh); MEASURED_REPORT_ONLY=1
# rewrites the plots and section from an earlier run's CSV files.
set -u
: "${MT_TRADEOFF:?}" "${OUT:?}"
QUICK=${QUICK:-0}
SHARED=${SHARED:-}
GNUPLOT=${GNUPLOT:-}
TRADEOFF_DIR=${TRADEOFF_DIR:-$(cd "$(dirname "$0")" && pwd)}
PROG=$MT_TRADEOFF/measured
[ -x "$PROG" ] || { echo "4-measured: $PROG not found (build it first)" >&2; exit 1; }
mkdir -p "$OUT"

START=$(date +%s)
A=$OUT/4-measured-analytic.csv
F=$OUT/4-measured-files.csv
if [ "${MEASURED_REPORT_ONLY:-0}" = 1 ] && [ -s "$A" ]; then
    # MEASURED_REPORT_ONLY=1: the plots and section again from an earlier
    # run's CSV files (its duration is kept beside them)
    ELAPSED=$(cat "$OUT/4-measured.seconds" 2>/dev/null || echo "?")
else
    set -- --out "$OUT"
    [ "$QUICK" = 1 ] && set -- "$@" --quick
    if [ -n "$SHARED" ] && [ -d "$SHARED/reference/scenes/brdfs" ]; then
        set -- "$@" --brdfs "$SHARED/reference/scenes/brdfs"
    fi
    rm -f "$F"
    "$PROG" "$@" || { echo "4-measured: $PROG failed" >&2; exit 1; }
    ELAPSED=$(($(date +%s) - START))
    echo "$ELAPSED" > "$OUT/4-measured.seconds"
fi
. "$TRADEOFF_DIR/lib.sh"
status=0

# Error against data size and against time per call, one series per form and
# material, selected from 4-measured-analytic.csv in gnuplot (columns: 3 N or
# bins, 4 bytes, 5 ns per call, 6 relative RMS error).
mats=$(awk -F, 'NR > 1 && $2 == "analytic" { print $1 }' "$A")
PLOTMD=
for what in size time; do
    if [ $what = size ]; then
        head="set title 'Measured BRDF forms of a plastic: error against data size'
set xlabel 'data size (bytes)'; set format x '10^{%L}'"
        col=4
    else
        ta=$(awk -F, 'NR > 1 && $2 == "analytic" { s += $5; n++ } END { printf "%.1f", s / n }' "$A")
        head="set title 'Measured BRDF forms of a plastic: error against time per f call'
set xlabel 'time per f call (ns, one thread)'; set format x '%g'; set xrange [20:20000]
set arrow from $ta, graph 0 to $ta, graph 1 nohead dt 3 lc rgb 'gray40'
set label 'analytic plastic' at $ta, graph 0.95 offset 0.5,0 tc rgb 'gray40'"
        col=5
    fi
    p="plot"; sep=""; pt=5
    IFS_SAVE=$IFS
    IFS='
'
    for m in $mats; do
        r=${m##* } # the roughness, the name's last word
        sel="strcol(1) eq '$m' && strcol(2) eq"
        p="$p$sep '4-measured-analytic.csv' using ($sel 'irregular' ? column($col) : NaN):(column(6)) with linespoints pt $pt lw 1.5 title 'irregular, N samples, roughness $r', \\
     '' using ($sel 'irregular' ? column($col) : NaN):(column(6)):(sprintf('N=%dk', column(3) / 1000)) with labels offset 0,0.8 font ',8' notitle"
        sep=", \\
    "
        if [ $what = size ]; then
            p="$p, \\
     '' using ($sel 'merl' ? column($col) : NaN):(column(6)) with linespoints pt $((pt + 2)) lw 1.5 dt 2 title 'MERL table, 90/k bins, roughness $r'"
        else
            # a coarse table costs what the full one costs: only the full one
            p="$p, \\
     '' using ($sel 'merl' && column(3) == 90 ? column($col) : NaN):(column(6)) with points pt $((pt + 2)) ps 1.8 title 'MERL table (90 bins), roughness $r'"
        fi
        pt=$((pt + 4))
    done
    IFS=$IFS_SAVE
    cmds="set logscale xy; set grid; set key bottom left box opaque
set ylabel 'relative RMS error of f'
$head
$p"
    md=$(tr_plot "4-measured-$what" "Measured BRDF forms: error against $( [ $what = size ] && echo "data size" || echo "time per call")" \
        "4-measured-analytic.csv" "$cmds" "size 800,520 enhanced font 'DejaVu Sans,10'") || status=1
    PLOTMD="$PLOTMD$md

"
done

MD=$OUT/4-measured.md
{
    echo "## 4. Measured BRDFs"
    echo
    echo "pbrt-v2 reads measured BRDFs in two forms: irregular samples (\`.brdf\`, a k-d search of"
    echo "the samples near the remapped direction pair, Gaussian-weighted: IrregIsotropicBRDF) and"
    echo "the MERL half-angle table (90 x 90 x 180 bins, the bin's value: RegularHalfangleBRDF)."
    echo "\`tradeoff/measured.c\` measures what each costs per call and how far it is from the"
    echo "BRDF it stands for. Error: the relative RMS difference of f over the three channels and"
    echo "$(if [ "$QUICK" = 1 ]; then echo 4000; else echo 100000; fi) direction pairs, both cosine-distributed (the projected solid angle; with wo uniform the"
    echo "few grazing pairs, where the microfacet f grows as 1/cos theta_o, dominate). Time:"
    echo "ns per f call, one thread's CPU time, median of 5 runs over 4096 pairs. Beside the RMS figure"
    echo "(which the lobes, the few pairs with a large f, dominate), the median over the pairs of the"
    echo "relative difference: the typical pair's error."
    echo
    echo "**Against a known truth.** pbrt-v2's plastic (Kd 0.35 0.12 0.08, Ks 0.3, Blinn exponent"
    echo "1/roughness) at two roughnesses stands for a measured material: irregular data of N pairs"
    echo "drawn uniformly with the plastic's values, and its MERL table (bin centres), full and"
    echo "averaged over k x k x k blocks of bins (90/k bins along theta_h; pbrt-v2 reads only the"
    echo "full resolution, so a coarse table is held at it: the same time per call, k^3 less data)."
    echo
    printf '%s' "$PLOTMD"
    echo "| material | form | N or bins | data (bytes) | ns per call | relative RMS error | median relative error |"
    echo "| --- | --- | --- | --- | --- | --- | --- |"
    awk -F, 'NR > 1 { printf "| %s | %s | %s | %s | %s | %s | %s |\n", $1, $2, ($2 == "analytic" ? "-" : $3), ($2 == "analytic" ? "-" : $4), $5, ($2 == "analytic" ? "0 (truth)" : $6), ($2 == "analytic" ? "0" : $7) }' "$A"
    echo
    awk -F, 'NR > 1 && $2 == "analytic" { ta[$1] = $5 }
        NR > 1 && $2 == "merl" && $3 == 90 { em[$1] = $6; dm[$1] = $7; tm[$1] = $5 }
        NR > 1 && $2 == "irregular" { if (!($1 in ei) || $3 > ni[$1]) { ni[$1] = $3; ei[$1] = $6; di[$1] = $7; ti[$1] = $5 } }
        END {
            for (m in em)
                printf "%s: the full MERL table is off by %.1f%% RMS (median %.2g%%) at %.0f ns a call (the analytic BRDF: %.0f ns); %d irregular samples are off by %.0f%% RMS (median %.2g%%) at %.0f ns a call.\n", m, 100 * em[m], 100 * dm[m], tm[m], ta[m], ni[m], 100 * ei[m], 100 * di[m], ti[m]
        }' "$A"
    echo
    if [ -s "$F" ]; then
        echo "**The real irregular files** of \`../shared/reference/scenes/brdfs\`, each against its"
        echo "own MERL table (tabulated from the irregular BRDF at bin centres): the table's error"
        echo "taking the irregular BRDF as the truth, the time per call of each form, and the time"
        echo "to tabulate."
        echo
        echo "| file | samples | irregular ns/call | MERL ns/call | speed-up | MERL RMS error | MERL median error | tabulation (s) |"
        echo "| --- | --- | --- | --- | --- | --- | --- | --- |"
        awk -F, 'NR > 1 { printf "| %s | %s | %s | %s | %.1fx | %.1f%% | %.2f%% | %s |\n", $1, $2, $3, $4, $3 / $4, 100 * $5, 100 * $6, $7 }' "$F"
        echo
    else
        echo "**The real irregular files** (\`../shared/reference/scenes/brdfs\`) were not measured:"
        echo "\`../shared\` is absent."
        echo
    fi
    echo "Measured by \`$(if [ "$QUICK" = 1 ]; then echo "make tradeoff QUICK=1"; else echo "make tradeoff"; fi)\` (\`tradeoff/4-measured.sh\`) in ${ELAPSED} s of wall time."
} > "$MD.tmp" && mv "$MD.tmp" "$MD"
echo "4-measured: wrote $A, $MD" >&2
exit $status
