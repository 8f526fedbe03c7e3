#!/bin/sh
# Measurement 3: texture filtering. $MT_TRADEOFF/filtering
# (tradeoff/filtering.c) measures, over a sweep of footprint sizes and
# anisotropies, each filter's error against a brute-force box average over
# the sample's footprint and its time per lookup, for the image map (none,
# trilinear, EWA with maxanisotropy 1 to 64, supersampling) and the
# checkerboard (aamode none, closedform, supersampling). This script plots
# them and writes the report section $OUT/3-filtering.md. Environment:
# MT_TRADEOFF, OUT, QUICK, GNUPLOT, TRADEOFF_DIR (tools/run-tradeoff.sh).
set -u
: "${MT_TRADEOFF:?}" "${OUT:?}"
QUICK=${QUICK:-0}
GNUPLOT=${GNUPLOT:-}
TRADEOFF_DIR=${TRADEOFF_DIR:-$(cd "$(dirname "$0")" && pwd)}
PROG=$MT_TRADEOFF/filtering
[ -x "$PROG" ] || { echo "3-filtering: $PROG not found (build it first)" >&2; exit 1; }
mkdir -p "$OUT"
START=$(date +%s)
if [ "${FILTERING_REPORT_ONLY:-0}" = 1 ] && [ -s "$OUT/3-filtering-checker.csv" ]; then :
elif [ "$QUICK" = 1 ]; then "$PROG" --out "$OUT" --quick; else "$PROG" --out "$OUT"; fi ||
    { echo "3-filtering: $PROG failed" >&2; exit 1; }
# FILTERING_REPORT_ONLY=1: the plots and section again from an earlier run's CSV
if [ "${FILTERING_REPORT_ONLY:-0}" = 1 ] && [ -s "$OUT/3-filtering.seconds" ]; then
    ELAPSED=$(cat "$OUT/3-filtering.seconds")
else
    ELAPSED=$(($(date +%s) - START))
    echo "$ELAPSED" > "$OUT/3-filtering.seconds"
fi
I=$OUT/3-filtering-imagemap.csv
C=$OUT/3-filtering-checker.csv
TMP=$(mktemp -d "${TMPDIR:-/tmp}/mt-filtering.XXXXXX") || exit 1
trap 'rm -rf "$TMP"' EXIT INT TERM

# Per mode (and parameter) over the whole sweep: the RMS of the groups' RMS
# errors (cell and wide truth) and the mean time per lookup.
overall() {
    awk -F, 'NR > 1 { k = $1 "," $2; if (!(k in n)) o[++m] = k; n[k]++; e[k] += $5 * $5; w[k] += $6 * $6; t[k] += $7 }
        END { for (i = 1; i <= m; i++) { k = o[i]; printf "%s,%.4g,%.4g,%.1f\n", k, sqrt(e[k] / n[k]), sqrt(w[k] / n[k]), t[k] / n[k] } }' "$1"
}
overall "$I" > "$TMP/i-overall.csv"
overall "$C" > "$TMP/c-overall.csv"

# series FILE MODE PARAM XCOL: "x error" rows of one mode, the RMS over the
# other sweep variable (XCOL 3: size, 4: anisotropy).
series() {
    awk -F, -v m="$2" -v p="$3" -v xc="$4" 'NR > 1 && $1 == m && $2 == p {
        x = $xc; if (!(x in n)) o[++k] = x; n[x]++; e[x] += $5 * $5 }
        END { for (i = 1; i <= k; i++) printf "%s %.5g\n", o[i], sqrt(e[o[i]] / n[o[i]]) }' "$1"
}

PLOTS=
if [ -n "$GNUPLOT" ]; then
    # error against time: one point per mode, EWA and supersampling as lines
    # overall rows: mode, parameter, error (cell), error (wide), ns per lookup
    awk -F, '$1 == "ewa" { print $5, $2, $3 }' "$TMP/i-overall.csv" > "$TMP/i-ewa.dat"
    awk -F, '$1 == "supersampled" { print $5, $2 * $2, $3 }' "$TMP/i-overall.csv" > "$TMP/i-ss.dat"
    awk -F, '$1 == "supersampled" { print $5, $2 * $2, $3 }' "$TMP/c-overall.csv" > "$TMP/c-ss.dat"
    for m in none trilinear trilinear-corrected; do
        awk -F, -v m=$m '$1 == m { print $5, $3 }' "$TMP/i-overall.csv" > "$TMP/i-$m.dat"
    done
    for m in none closedform; do
        awk -F, -v m=$m '$1 == m { print $5, $3 }' "$TMP/c-overall.csv" > "$TMP/c-$m.dat"
    done
    for x in 3 4; do
        for m in "none 0" "trilinear 0" "trilinear-corrected 0" "ewa 8" "ewa 64" "supersampled 4"; do
            set -- $m; series "$I" "$1" "$2" $x > "$TMP/i-$1-$2-$x.dat"
        done
        for m in "none 0" "closedform 0" "supersampled 4" "supersampled 16"; do
            set -- $m; series "$C" "$1" "$2" $x > "$TMP/c-$1-$2-$x.dat"
        done
    done
    gp_head() {
        if [ -f "$TRADEOFF_DIR/style.gp" ]; then echo "load '$TRADEOFF_DIR/style.gp'"; fi
        echo "set terminal pngcairo size 1100,560 enhanced font 'DejaVu Sans,10'"
        # the data files here are whitespace-separated (the shared style reads CSV)
        echo "set datafile separator whitespace"
        echo "set output '$OUT/$1'"
        echo "set grid; set logscale xy; set format y '10^{%L}'; set format x '%g'; set key below horizontal maxcols 2 width -4; set bmargin 9"
        echo "set multiplot layout 1,2"
    }
    {
        gp_head 3-filtering-time.png
        echo "set xlabel 'time per lookup (ns, one thread)'; set ylabel 'RMS error (texture values span [0, 1])'"
        echo "set title 'Image map (512^2): error against cost, whole sweep'"
        echo "plot '$TMP/i-ewa.dat' using 1:3 with linespoints pt 7 lw 1.5 title 'EWA, maxanisotropy 1..64', \
'' using 1:3:(sprintf('%d', \$2)) with labels offset 1.2,0.6 font ',8' notitle, \
'$TMP/i-ss.dat' using 1:3 with linespoints pt 5 lw 1.5 dt 2 title 'supersampled, 4..64 bilinear lookups', \
'$TMP/i-none.dat' using 1:2 with points pt 9 ps 1.6 title 'none (bilinear, level 0)', \
'$TMP/i-trilinear.dat' using 1:2 with points pt 11 ps 1.6 title 'trilinear (pbrt-v2 width)', \
'$TMP/i-trilinear-corrected.dat' using 1:2 with points pt 13 ps 1.6 title 'trilinear (corrected width)'"
        echo "set title 'Checkerboard: error against cost, whole sweep'"
        echo "plot '$TMP/c-ss.dat' using 1:3 with linespoints pt 5 lw 1.5 dt 2 title 'supersampled, 4..256 lookups', \
'' using 1:3:(sprintf('%d', \$2)) with labels offset 1.2,0.6 font ',8' notitle, \
'$TMP/c-none.dat' using 1:2 with points pt 9 ps 1.6 title 'aamode none', \
'$TMP/c-closedform.dat' using 1:2 with points pt 11 ps 1.6 title 'aamode closedform'"
        echo "unset multiplot"
    } > "$TMP/time.gp"
    for x in 3 4; do
        if [ $x = 3 ]; then name=3-filtering-size.png; else name=3-filtering-aniso.png; fi
        {
            gp_head $name
            echo "set ylabel 'RMS error (texture values span [0, 1])'"
            if [ $x = 3 ]; then
                echo "set xlabel 'footprint: major semi-axis |d0| (texels)'; set title 'Image map: error against footprint size (all anisotropies)'"
            else
                echo "set xlabel 'anisotropy |d0| / |d1|'; set title 'Image map: error against anisotropy (all sizes)'"
            fi
            echo "plot '$TMP/i-none-0-$x.dat' with linespoints pt 9 lw 1.5 title 'none', \
'$TMP/i-trilinear-0-$x.dat' with linespoints pt 11 lw 1.5 title 'trilinear (pbrt-v2 width)', \
'$TMP/i-trilinear-corrected-0-$x.dat' with linespoints pt 13 lw 1.5 title 'trilinear (corrected width)', \
'$TMP/i-ewa-8-$x.dat' with linespoints pt 7 lw 1.5 title 'EWA, maxanisotropy 8 (default)', \
'$TMP/i-ewa-64-$x.dat' with linespoints pt 6 lw 1.5 title 'EWA, maxanisotropy 64', \
'$TMP/i-supersampled-4-$x.dat' with linespoints pt 5 lw 1.5 dt 2 title 'supersampled 4x4'"
            if [ $x = 3 ]; then
                echo "set xlabel 'footprint: major semi-axis |d0| (checks)'; set title 'Checkerboard: error against footprint size (all anisotropies)'"
            else
                echo "set xlabel 'anisotropy |d0| / |d1|'; set title 'Checkerboard: error against anisotropy (all sizes)'"
            fi
            echo "plot '$TMP/c-none-0-$x.dat' with linespoints pt 9 lw 1.5 title 'aamode none', \
'$TMP/c-closedform-0-$x.dat' with linespoints pt 11 lw 1.5 title 'aamode closedform', \
'$TMP/c-supersampled-4-$x.dat' with linespoints pt 5 lw 1.5 dt 2 title 'supersampled 4x4', \
'$TMP/c-supersampled-16-$x.dat' with linespoints pt 4 lw 1.5 dt 2 title 'supersampled 16x16'"
            echo "unset multiplot"
        } > "$TMP/$x.gp"
    done
    for g in time 3 4; do
        "$GNUPLOT" "$TMP/$g.gp" || { echo "3-filtering: gnuplot failed on $g" >&2; exit 1; }
    done
    PLOTS="3-filtering-time.png 3-filtering-aniso.png 3-filtering-size.png"
fi

MD=$OUT/3-filtering.md
{
    echo "## 3. Texture filtering"
    echo
    echo "What each texture filter costs and how close it comes to the ideal answer. A lookup gets a"
    echo "point and its screen-space differentials d0, d1, which pbrt-v2 scales to the spacing of the"
    echo "samples; the ideal answer is the average of the texture over the sample's own cell, the"
    echo "parallelogram p + a d0 + b d1 with a, b in [-1/2, 1/2] (what many unfiltered samples average"
    echo "to under a box pixel filter), computed by brute force in double on a fine grid, independently"
    echo "of materia's filters (\`tradeoff/filtering.c\`). pbrt-v2's filters span more than the cell"
    echo "(trilinear a square of side 2 max|d|, closedform a box of +-max|d|, EWA an ellipse with the"
    echo "differentials as semi-axes): their error against the box over a, b in [-1, 1] is the column"
    echo "\"wide\" below and in the CSV files."
    echo
    echo "- **Image map**: a 512 x 512 periodic pattern of eight plane waves, 2 to 205 cycles across"
    echo "  the image (up to 0.4 cycles per texel), amplitudes falling as 1/sqrt(frequency), values in"
    echo "  [0, 1]; the continuous texture is the bilinear interpolant of its texels. Modes through the"
    echo "  public MIP-map API as pbrt-v2's \`imagemap\` uses it: no filtering (bilinear at level 0),"
    echo "  \`\"bool trilinear\" \"true\"\` (pbrt-v2's width 2 max|d|, and the corrected width max|d|),"
    echo "  EWA (the default) with \`\"float maxanisotropy\"\` 1 to 64, and supersampling by the caller:"
    echo "  S x S unfiltered lookups over the cell."
    echo "- **Checkerboard**: pbrt-v2's float \`checkerboard\` (tex1 1, tex2 0) through the public"
    echo "  texture API, \`\"string aamode\"\` \`none\` and \`closedform\` (pbrt-v2 has no supersampling"
    echo "  aamode), and S x S lookups with aamode none over the cell."
    if [ "$QUICK" = 1 ]; then
        echo "- Sweep (reduced): footprint sizes |d0| 0.5, 2, 8, 32 texels (0.03, 0.3, 1 checks), anisotropies"
        echo "  1, 4, 16, 64, 40 (30) random footprints each."
    else
        echo "- Sweep: footprint sizes |d0| 0.25 to 64 texels in powers of 2 (0.01 to 3 checks),"
        echo "  anisotropies |d0|/|d1| 1 to 64 in powers of 2, 200 (150) random footprints each, at random"
        echo "  points and orientations."
    fi
    echo "- Error: RMS of lookup - truth; time: ns per lookup on one thread (CPU time, median of 3 runs"
    echo "  of 8 passes)."
    echo
    if [ -n "$PLOTS" ]; then
        for p in $PLOTS; do echo "![$p]($p)"; echo; done
    else
        echo "gnuplot was not found: the data are in \`3-filtering-imagemap.csv\` and"
        echo "\`3-filtering-checker.csv\` (mode, parameter, size, anisotropy, RMS error, RMS error"
        echo "against the wide box, ns per lookup); plot error (column 5) against ns per lookup (7),"
        echo "size (3) or anisotropy (4) on log-log axes, one series per mode and parameter."
        echo
    fi
    echo "Over the whole sweep (RMS of the groups' errors, mean time per lookup):"
    echo
    echo "| texture | mode | parameter | RMS error (cell) | RMS error (wide) | ns per lookup |"
    echo "| --- | --- | --- | --- | --- | --- |"
    awk -F, '{ printf "| image map | %s | %s | %s | %s | %s |\n", $1, ($1 == "ewa" ? "maxanisotropy " $2 : ($1 == "supersampled" ? $2 "x" $2 : "-")), $3, $4, $5 }' "$TMP/i-overall.csv"
    awk -F, '{ printf "| checkerboard | %s | %s | %s | %s | %s |\n", $1, ($1 == "supersampled" ? $2 "x" $2 : "-"), $3, $4, $5 }' "$TMP/c-overall.csv"
    echo
    # conclusions from the data: the cheapest supersampling that beats EWA 8
    # and closedform, and the relative costs
    awk -F, -v file=i 'FILENAME ~ /i-overall/ { if ($1 == "ewa" && $2 == 8) { ee = $3; te = $5 } if ($1 == "none") { en = $3; tn = $5 }
                               if ($1 == "trilinear") { et = $3; tt = $5 } if ($1 == "ewa" && $2 == 64) { e64 = $3; t64 = $5 }
                               if ($1 == "supersampled") { se[++ns] = $3; st[ns] = $5; sp[ns] = $2 } }
        FILENAME ~ /c-overall/ { if ($1 == "closedform") { ec = $3; tc = $5 } if ($1 == "none") { ecn = $3; tcn = $5 }
                               if ($1 == "supersampled") { cse[++ncs] = $3; cst[ncs] = $5; csp[ncs] = $2 } }
        END {
            printf "Image map: EWA at the default maxanisotropy 8 has %.2g of the error of no filtering (%.3g against %.3g) at %.1fx its cost; ", ee / en, ee, en, te / tn
            printf "trilinear %.3g at %.1fx; maxanisotropy 64 gives %.3g at %.1fx. ", et, tt / tn, e64, t64 / tn
            b = 0; for (i = 1; i <= ns; i++) if (!b && se[i] <= ee) b = i
            if (b) printf "Supersampling needs %dx%d lookups (%.0f ns, %.1fx EWA'\''s time) to match EWA'\''s error.\n", sp[b], sp[b], st[b], st[b] / te
            else printf "No supersampling rate measured (up to %dx%d, %.0f ns) matches EWA'\''s error.\n", sp[ns], sp[ns], st[ns]
            printf "Checkerboard: closedform has %.2g of the error of aamode none (%.3g against %.3g) at %.1fx its cost; ", ec / ecn, ec, ecn, tc / tcn
            b = 0; for (i = 1; i <= ncs; i++) if (!b && cse[i] <= ec) b = i
            if (b) printf "supersampling needs %dx%d lookups (%.0f ns, %.0fx closedform'\''s time) to match it.\n", csp[b], csp[b], cst[b], cst[b] / tc
            else printf "no supersampling rate measured matches it.\n"
        }' "$TMP/i-overall.csv" "$TMP/c-overall.csv"
    echo
    echo "Measured by \`$(if [ "$QUICK" = 1 ]; then echo "make tradeoff QUICK=1"; else echo "make tradeoff"; fi)\` (\`tradeoff/3-filtering.sh\`) in ${ELAPSED} s of wall time."
} > "$MD.tmp" && mv "$MD.tmp" "$MD"
echo "3-filtering: wrote $I, $C, $MD" >&2
